//! The GLB container (glTF 2.0's binary form), written: for the benches, tests and
//! examples that make glTF files. gltf_file.rs reads them.

/// A `.glb` file of the glTF document `json` and the binary chunk `bin` (its buffer 0),
/// each padded to four bytes as the container requires (the JSON with spaces).
pub fn glb_file(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let padding = |n: usize| (4 - n % 4) % 4;
    let (json_len, bin_len) = (
        json.len() + padding(json.len()),
        bin.len() + padding(bin.len()),
    );
    let total = 12 + 8 + json_len + 8 + bin_len;
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json_len as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json);
    out.resize(out.len() + padding(json.len()), b' ');
    out.extend((bin_len as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out.resize(out.len() + padding(bin.len()), 0);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_container_reads_back_as_the_document_and_its_chunk() {
        let json = br#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":5}]}"#;
        let file = glb_file(json, &[1, 2, 3, 4, 5]);
        assert_eq!(file.len() % 4, 0);
        let read = gltf::Gltf::from_slice(&file).unwrap();
        assert_eq!(
            read.blob.as_deref().map(|b| &b[..5]),
            Some(&[1u8, 2, 3, 4, 5][..])
        );
        assert_eq!(read.buffers().next().unwrap().length(), 5);
    }
}
