//! A granular deposit measured as experiments measure it: the height of a
//! body's top surface along x, its toe where it thins below a fraction of
//! the body's initial height, and the share of its mass beyond the toe.
//!
//! A material point is a parcel of continuum, so a body's surface over a
//! column of the grid is the top of its highest point's domain there, and
//! a lone point thrown ahead of the flow is a thin sheet of material, not
//! the deposit's edge. Published collapses read the toe where the deposit
//! is a few percent of the column's height thick (Lube et al. 2005, J.
//! Fluid Mech. 538, 77–87, and Bui et al. 2008, Int. J. Numer. Anal.
//! Methods Geomech. 32, 1537–1570, from photographs of the deposit).

use crate::math::{DVec2, Real};

/// The thicknesses, as fractions of the body's initial height H0, at which
/// a deposit's toe is read: 2% and 5% of H0.
pub const TOE_LEVELS: [Real; 2] = [0.02, 0.05];

/// Where a body's deposit is measured from: its initial base and height.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepositDatum {
    /// The lowest y of the body's point domains at the start (m).
    pub base: Real,
    /// H0: the highest y of the body's point domains at the start, less the
    /// base (m).
    pub height: Real,
}

impl DepositDatum {
    /// The datum of a body whose points sit at `positions` with domain
    /// half-sizes `half_sizes`.
    pub fn of(positions: &[DVec2], half_sizes: &[DVec2]) -> Self {
        let (mut base, mut top) = (Real::INFINITY, Real::NEG_INFINITY);
        for (x, half) in positions.iter().zip(half_sizes) {
            base = base.min(x.y - half.y);
            top = top.max(x.y + half.y);
        }
        Self {
            base,
            height: top - base,
        }
    }
}

/// A body's surface along x: the height above the datum's base of its
/// highest point domain over each bin, 0 where it has no point.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceProfile {
    /// The x where the first bin starts (m).
    pub start: Real,
    /// The bins' width (m).
    pub bin: Real,
    /// The height over each bin (m), from `start` on.
    pub heights: Vec<Real>,
}

impl SurfaceProfile {
    /// An empty profile of `bins` bins of width `bin` from x = `start`.
    pub fn new(start: Real, bin: Real, bins: usize) -> Self {
        Self {
            start,
            bin,
            heights: vec![0.0; bins],
        }
    }

    /// Measures the surface of the points at `positions`, with domain
    /// half-sizes `half_sizes`, above `base`. A point outside the bins is
    /// left out.
    pub fn measure(&mut self, positions: &[DVec2], half_sizes: &[DVec2], base: Real) {
        self.heights.fill(0.0);
        for (x, half) in positions.iter().zip(half_sizes) {
            let k = ((x.x - self.start) / self.bin).floor();
            if k >= 0.0 && (k as usize) < self.heights.len() {
                let height = &mut self.heights[k as usize];
                *height = height.max(x.y + half.y - base);
            }
        }
    }

    /// The x at the centre of bin `k` (m).
    pub fn centre(&self, k: usize) -> Real {
        self.start + (k as Real + 0.5) * self.bin
    }

    /// The toe at `level` (m): scanning along +x from the highest bin, the
    /// x where the surface first falls below `level`, linear between the
    /// centres of the last bin at or above it and the first below. The end
    /// of the last bin if it never does; NaN for a profile with no point.
    pub fn toe(&self, level: Real) -> Real {
        let highest =
            self.heights
                .iter()
                .enumerate()
                .fold(None, |best: Option<(usize, Real)>, (k, &h)| match best {
                    Some((_, b)) if b >= h => best,
                    _ if h > 0.0 => Some((k, h)),
                    _ => best,
                });
        let Some((first, _)) = highest else {
            return Real::NAN;
        };
        let below = (first..self.heights.len()).find(|&k| self.heights[k] < level);
        match below {
            None => self.start + self.heights.len() as Real * self.bin,
            Some(k) if k == first => self.centre(k),
            Some(k) => {
                let (above, under) = (self.heights[k - 1], self.heights[k]);
                self.centre(k - 1) + (above - level) / (above - under) * self.bin
            }
        }
    }
}

/// The share of the total of `mass` whose points lie beyond x = `toe`.
pub fn share_beyond(toe: Real, positions: &[DVec2], mass: &[Real]) -> Real {
    let (mut beyond, mut total) = (0.0, 0.0);
    for (x, m) in positions.iter().zip(mass) {
        total += m;
        if x.x > toe {
            beyond += m;
        }
    }
    beyond / total
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A wedge of points, one per 1 cm square, falling from 10 cm at x = 0
    /// to nothing at x = 1 m, and one point thrown to x = 2 m.
    fn wedge() -> (Vec<DVec2>, Vec<DVec2>) {
        let mut positions = Vec::new();
        for i in 0..100 {
            let x = 0.005 + 0.01 * i as Real;
            let height = 0.1 * (1.0 - x);
            for j in 0..((height / 0.01).round() as usize) {
                positions.push(DVec2::new(x, 0.005 + 0.01 * j as Real));
            }
        }
        positions.push(DVec2::new(2.0, 0.005));
        let half = vec![DVec2::splat(0.005); positions.len()];
        (positions, half)
    }

    #[test]
    fn the_toe_is_where_the_surface_thins_below_its_level_not_the_farthest_point() {
        let (positions, half) = wedge();
        let datum = DepositDatum::of(&positions, &half);
        assert_eq!(datum.base, 0.0);
        assert!((datum.height - 0.1).abs() < 1e-12);
        let mut profile = SurfaceProfile::new(0.0, 0.01, 300);
        profile.measure(&positions, &half, datum.base);
        assert!((profile.heights[0] - 0.1).abs() < 1e-12);
        // The surface steps down 1 cm every 10 cm, its last centimetre over
        // x = 0.85 to 0.95 m, so it falls below 5 mm halfway between the
        // centres at 0.945 (1 cm) and 0.955 (nothing) m.
        let toe = profile.toe(0.005);
        assert!((toe - 0.95).abs() < 1e-9, "{toe}");
        // The thrown point is a bin of its own, far past the toe.
        assert!(profile.heights[200] > 0.0);
        let mass = vec![1.0; positions.len()];
        let spray = share_beyond(toe, &positions, &mass);
        assert!((spray - 1.0 / positions.len() as Real).abs() < 1e-15);
    }

    #[test]
    fn a_surface_that_never_thins_enough_reaches_the_end_and_no_point_gives_nan() {
        let (positions, half) = wedge();
        let mut profile = SurfaceProfile::new(0.0, 0.01, 50);
        profile.measure(&positions, &half, 0.0);
        assert_eq!(profile.toe(0.001), 0.5);
        profile.measure(&[], &[], 0.0);
        assert!(profile.toe(0.001).is_nan());
    }
}
