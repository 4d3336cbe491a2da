//! A hash of the simulation state for bit-identity checks.

use crate::components::MaterialPoints;
use crate::math::Real;

/// 64-bit FNV-1a over the little-endian bytes of the state.
#[derive(Clone, Copy, Debug)]
pub struct StateHasher(u64);

impl Default for StateHasher {
    fn default() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
}

impl StateHasher {
    /// Mixes in raw bytes.
    pub fn add_bytes(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 ^= u64::from(*b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    /// Mixes in an integer.
    pub fn add_u64(&mut self, value: u64) {
        self.add_bytes(&value.to_le_bytes());
    }

    /// Mixes in floats, bit for bit.
    pub fn add_reals(&mut self, values: impl IntoIterator<Item = Real>) {
        for v in values {
            self.add_bytes(&v.to_bits().to_le_bytes());
        }
    }

    /// Mixes in every state column of a body.
    pub fn add_points(&mut self, points: &MaterialPoints) {
        self.add_u64(points.len() as u64);
        self.add_reals(points.position.iter().flat_map(|v| v.to_array()));
        self.add_reals(points.velocity.iter().flat_map(|v| v.to_array()));
        self.add_reals(
            points
                .deformation_gradient
                .iter()
                .flat_map(|f| f.to_cols_array()),
        );
        self.add_reals(
            points
                .velocity_gradient
                .iter()
                .flat_map(|l| l.to_cols_array()),
        );
        self.add_reals(
            points
                .affine_gradient
                .iter()
                .flat_map(|c| c.to_cols_array()),
        );
        self.add_reals(points.volume.iter().copied());
        self.add_reals(points.stress.iter().flat_map(|s| s.to_array()));
        self.add_reals(points.strain.iter().flat_map(|s| s.to_array()));
    }

    /// The hash.
    pub fn finish(&self) -> u64 {
        self.0
    }
}

/// Hashes formatted text as it is written, e.g. `write!(hasher, "{x:?}")`,
/// without building the string.
impl std::fmt::Write for StateHasher {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        self.add_bytes(s.as_bytes());
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_fnv1a_reference_values() {
        // Published FNV-1a 64 test vectors.
        let mut h = StateHasher::default();
        assert_eq!(h.finish(), 0xcbf29ce484222325);
        h.add_bytes(b"a");
        assert_eq!(h.finish(), 0xaf63dc4c8601ec8c);
        let mut h = StateHasher::default();
        h.add_bytes(b"foobar");
        assert_eq!(h.finish(), 0x85944171f73967e8);
    }
}
