//! With the `denoise` feature, prism's programs find Intel Open Image Denoise where they
//! were linked against it (OIDN_DIR's lib/), without LD_LIBRARY_PATH.

fn main() {
    println!("cargo:rerun-if-env-changed=OIDN_DIR");
    let unix = std::env::var("CARGO_CFG_UNIX").is_ok();
    if std::env::var_os("CARGO_FEATURE_DENOISE").is_some()
        && unix
        && let Some(dir) = std::env::var_os("OIDN_DIR")
    {
        let lib = std::path::Path::new(&dir).join("lib");
        println!("cargo:rustc-link-arg=-Wl,-rpath,{}", lib.display());
    }
}
