//! The geometry of two overlapping contact disks (section 3.3): the
//! body–body contacts' normal, overlap and contact point.

use crate::math::{DVec2, Real};

/// Two overlapping disks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiskOverlap {
    /// Unit normal from the second disk's centre to the first's.
    pub normal: DVec2,
    /// How far the disks overlap along the normal (m), > 0.
    pub overlap: Real,
    /// The middle of the overlap on the line of centres: the contact point.
    pub at: DVec2,
    /// The first centre less the second.
    pub separation: DVec2,
}

/// The overlap of the disk at `xp` of radius `rp` with the disk at `xq` of
/// radius `rq`; `None` if they do not overlap or share their centre (no
/// normal).
pub fn disk_overlap(xp: DVec2, rp: Real, xq: DVec2, rq: Real) -> Option<DiskOverlap> {
    let separation = xp - xq;
    let distance = separation.length();
    let overlap = rp + rq - distance;
    if overlap <= 0.0 || distance == 0.0 {
        return None;
    }
    let normal = separation / distance;
    Some(DiskOverlap {
        normal,
        overlap,
        at: xq + normal * (rq - 0.5 * overlap),
        separation,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlapping_disks_meet_in_the_middle_of_their_overlap() {
        let o = disk_overlap(DVec2::new(1.5, 0.0), 1.0, DVec2::ZERO, 1.0).expect("overlap");
        assert_eq!(o.normal, DVec2::X);
        assert_eq!(o.overlap, 0.5);
        assert_eq!(o.at, DVec2::new(0.75, 0.0));
        assert!(disk_overlap(DVec2::new(2.0, 0.0), 1.0, DVec2::ZERO, 1.0).is_none());
        assert!(disk_overlap(DVec2::ZERO, 1.0, DVec2::ZERO, 1.0).is_none());
    }
}
