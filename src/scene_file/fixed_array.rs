//! Arrays of a fixed length in the scene file (a position's three numbers, a triangle's
//! three corners), read so that too many elements are refused as too few are: serde's own
//! arrays stop reading after N and drop the rest, so `center = [0, 0, 0, 99]` would pass.

use serde::de::{Deserialize, Deserializer, Error, SeqAccess, Visitor};
use std::fmt;
use std::marker::PhantomData;
use std::ops::{Deref, DerefMut};

/// Exactly N values of T.
#[derive(Clone, Copy, PartialEq)]
pub struct Fixed<T, const N: usize>(pub [T; N]);

/// Shown as the list the file wrote (messages quote it), not as a wrapper.
impl<T: std::fmt::Debug, const N: usize> std::fmt::Debug for Fixed<T, N> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

impl<T, const N: usize> Deref for Fixed<T, N> {
    type Target = [T; N];
    fn deref(&self) -> &[T; N] {
        &self.0
    }
}

impl<T, const N: usize> DerefMut for Fixed<T, N> {
    fn deref_mut(&mut self) -> &mut [T; N] {
        &mut self.0
    }
}

impl<T, const N: usize> From<[T; N]> for Fixed<T, N> {
    fn from(values: [T; N]) -> Self {
        Self(values)
    }
}

impl<T, const N: usize> From<Fixed<T, N>> for [T; N] {
    fn from(values: Fixed<T, N>) -> Self {
        values.0
    }
}

impl From<Fixed<f32, 3>> for glam::Vec3 {
    fn from(v: Fixed<f32, 3>) -> Self {
        glam::Vec3::from_array(v.0)
    }
}

impl From<Fixed<f64, 3>> for glam::DVec3 {
    fn from(v: Fixed<f64, 3>) -> Self {
        glam::DVec3::from_array(v.0)
    }
}

struct FixedVisitor<T, const N: usize>(PhantomData<T>);

impl<'de, T: Deserialize<'de>, const N: usize> Visitor<'de> for FixedVisitor<T, N> {
    type Value = Fixed<T, N>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "an array of {N}")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut values = Vec::with_capacity(N);
        while let Some(value) = seq.next_element::<T>()? {
            if values.len() == N {
                // Counted to the end (within the file's own size) so the message says how many.
                let mut count = N + 1;
                while seq.next_element::<serde::de::IgnoredAny>()?.is_some() {
                    count += 1;
                }
                return Err(A::Error::invalid_length(count, &self));
            }
            values.push(value);
        }
        let len = values.len();
        values
            .try_into()
            .map(Fixed)
            .map_err(|_| A::Error::invalid_length(len, &self))
    }
}

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Fixed<T, N> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_seq(FixedVisitor::<T, N>(PhantomData))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Deserialize, Debug)]
    struct Doc {
        v: Fixed<f64, 3>,
        corners: Option<Fixed<Fixed<f64, 2>, 2>>,
    }

    #[test]
    fn exactly_n_elements_are_taken() {
        let doc: Doc = toml::from_str("v = [1, 2, 3]\ncorners = [[1, 2], [3, 4]]").unwrap();
        assert_eq!(*doc.v, [1.0, 2.0, 3.0]);
        assert_eq!(doc.corners.unwrap()[1][0], 3.0);
        for (text, needle) in [
            (
                "v = [0, 0, 0, 99, \"x\", true]",
                "invalid length 6, expected an array of 3",
            ),
            ("v = [0, 0]", "invalid length 2, expected an array of 3"),
            (
                "v = [0, 0, 0]\ncorners = [[1, 2], [3, 4], [5, 6]]",
                "invalid length 3",
            ),
            (
                "v = [0, 0, 0]\ncorners = [[1, 2], [3, 4, 5]]",
                "invalid length 3, expected an array of 2",
            ),
        ] {
            let e = toml::from_str::<Doc>(text).unwrap_err();
            assert!(e.to_string().contains(needle), "{text}: {e}");
        }
    }
}
