//! The bearing capacity factor N_q of a smooth rigid footing on a weightless,
//! cohesionless Mohr–Coulomb soil under a surcharge q, by the method of
//! stress characteristics (Sokolovskii 1965), as a strip in plane strain or as
//! a circle in axisymmetry. In axisymmetry the hoop stress is the minor
//! principal stress (the Haar–von Kármán hypothesis; Cox, Eason and Hopkins
//! 1961), which the radial outflow under a footing makes the consistent one.
//!
//! In the plane (x, y), y downward into the soil and compression positive,
//! the stresses at the limit are σ_x = p (1 + sin φ cos 2ψ), σ_y =
//! p (1 − sin φ cos 2ψ), τ_xy = p sin φ sin 2ψ, with ψ the angle from x to
//! the major principal stress. Along the two families of characteristics,
//! of directions θ = ψ ± μ with μ = π/4 − φ/2, equilibrium reads
//!
//!   dp ± 2 p tan φ dψ = −2 p tan φ sin μ cos ψ ds / x   (axisymmetry),
//!
//! with no right-hand side in plane strain (ds the arc length along e(θ),
//! x the radius). The net is built from the free surface beside the footing
//! (ψ = 0, σ_y = q), through the fan centred on the footing's edge, to the
//! footing's base (ψ = π/2, no shear), and N_q is the mean of σ_y on the
//! base over q: a plain mean on the strip, weighted by the radius on the
//! circle. In plane strain this reproduces Prandtl's closed form.

use mpdem::geometry::Geometry;
use mpdem::math::Real;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

/// A node of the net: its position (the footing's edge at x = 1, y = 0)
/// and its stress state (p, ψ).
#[derive(Clone, Copy, Debug)]
struct Node {
    x: Real,
    y: Real,
    p: Real,
    psi: Real,
}

/// The soil's friction angle and the geometry, with the constants of the
/// characteristic relations.
struct Soil {
    tan_phi: Real,
    mu: Real,
    axisymmetric: bool,
}

impl Soil {
    /// The right-hand side's rate along a characteristic, per unit of arc
    /// length: −2 p tan φ sin μ cos ψ / x in axisymmetry, zero in the plane.
    fn source(&self, node: &Node) -> Real {
        if self.axisymmetric {
            -2.0 * node.p * self.tan_phi * self.mu.sin() * node.psi.cos() / node.x
        } else {
            0.0
        }
    }

    /// The node where the plus characteristic through `a` (θ = ψ + μ) meets
    /// the minus characteristic through `b` (θ = ψ − μ), by the trapezoidal
    /// rule iterated to convergence.
    fn interior(&self, a: &Node, b: &Node) -> Node {
        let mut node = Node {
            x: 0.5 * (a.x + b.x),
            y: 0.5 * (a.y + b.y),
            p: 0.5 * (a.p + b.p),
            psi: 0.5 * (a.psi + b.psi),
        };
        for _ in 0..50 {
            let theta_a = 0.5 * (a.psi + node.psi) + self.mu;
            let theta_b = 0.5 * (b.psi + node.psi) - self.mu;
            let (slope_a, slope_b) = (theta_a.tan(), theta_b.tan());
            let x = (b.y - a.y + slope_a * a.x - slope_b * b.x) / (slope_a - slope_b);
            let y = a.y + slope_a * (x - a.x);
            let arc_a = (x - a.x) * theta_a.cos() + (y - a.y) * theta_a.sin();
            let arc_b = (x - b.x) * theta_b.cos() + (y - b.y) * theta_b.sin();
            let moved = Node { x, y, ..node };
            let source_a = 0.5 * (self.source(a) + self.source(&moved)) * arc_a;
            let source_b = 0.5 * (self.source(b) + self.source(&moved)) * arc_b;
            // p − p_a + k_a (ψ − ψ_a) = source_a and p − p_b − k_b (ψ − ψ_b) = source_b.
            let k_a = self.tan_phi * (a.p + node.p);
            let k_b = self.tan_phi * (b.p + node.p);
            let psi = (a.p + k_a * a.psi + source_a - (b.p - k_b * b.psi + source_b)) / (k_a + k_b);
            let p = a.p + k_a * (a.psi - psi) + source_a;
            let next = Node { x, y, p, psi };
            let settled = (next.x - node.x).abs() + (next.y - node.y).abs() < 1e-13
                && (next.p - node.p).abs() < 1e-12 * next.p;
            node = next;
            if settled {
                break;
            }
        }
        node
    }

    /// The node where the minus characteristic through `b` reaches the
    /// footing's smooth base (y = 0, ψ = π/2).
    fn on_base(&self, b: &Node) -> Node {
        let mut node = Node {
            x: b.x,
            y: 0.0,
            p: b.p,
            psi: FRAC_PI_2,
        };
        for _ in 0..50 {
            let theta = 0.5 * (b.psi + node.psi) - self.mu;
            let x = b.x - b.y / theta.tan();
            let arc = (x - b.x) * theta.cos() - b.y * theta.sin();
            let moved = Node { x, ..node };
            let source = if x > 0.0 {
                0.5 * (self.source(b) + self.source(&moved)) * arc
            } else {
                self.source(b) * arc
            };
            let p = b.p + self.tan_phi * (b.p + node.p) * (node.psi - b.psi) + source;
            let settled = (x - node.x).abs() < 1e-13 && (p - node.p).abs() < 1e-12 * p;
            node = Node { x, p, ..node };
            if settled {
                break;
            }
        }
        node
    }
}

/// N_q of a smooth rigid footing on a weightless, cohesionless soil of
/// friction angle φ (degrees, above zero): the mean vertical stress under a
/// strip ([`Geometry::PlaneStrain`]) or a circle ([`Geometry::Axisymmetric`])
/// at collapse over the surcharge. `fan_rays` sets the net's fineness: the
/// fan at the edge has that many rays, and the free surface is cut into
/// steps of a quarter of the footing's half width over that number.
pub fn smooth_footing_nq(
    friction_angle_degrees: Real,
    geometry: Geometry,
    fan_rays: usize,
) -> Real {
    let phi = friction_angle_degrees.to_radians();
    let soil = Soil {
        tan_phi: phi.tan(),
        mu: FRAC_PI_4 - phi / 2.0,
        axisymmetric: geometry == Geometry::Axisymmetric,
    };
    let step = 0.25 / fan_rays as Real;
    // On the free surface σ_y = q = 1 is the minor principal stress.
    let surface_p = 1.0 / (1.0 - phi.sin());
    // The fan at the edge: plus characteristics from (1, 0), ψ from 0 to
    // π/2; across it the minus relation holds with ds = 0.
    let mut previous: Vec<Node> = (0..=fan_rays)
        .map(|ray| {
            let psi = FRAC_PI_2 * ray as Real / fan_rays as Real;
            Node {
                x: 1.0,
                y: 0.0,
                p: surface_p * (2.0 * soil.tan_phi * psi).exp(),
                psi,
            }
        })
        .collect();
    // The base's nodes from the edge inward: (radius, σ_y).
    let edge = previous[fan_rays];
    let mut base = vec![(edge.x, edge.p * (1.0 + phi.sin()))];
    for char_index in 1.. {
        // The minus characteristic from the surface node at 1 + index step,
        // inward: through the passive zone, across the fan's rays and the
        // plus characteristics from the base's earlier nodes, to the base.
        let mut current = Vec::with_capacity(previous.len() + 2);
        current.push(Node {
            x: 1.0 + char_index as Real * step,
            y: 0.0,
            p: surface_p,
            psi: 0.0,
        });
        for earlier in &previous {
            let next = soil.interior(earlier, current.last().expect("one node"));
            current.push(next);
        }
        let reached = soil.on_base(current.last().expect("one node"));
        current.push(reached);
        let stress = reached.p * (1.0 + phi.sin());
        if reached.x <= 0.5 * step {
            // The axis: σ_y carried to x = 0 along the last stretch.
            let (x0, s0) = *base.last().expect("the edge");
            base.push((0.0, s0 - (stress - s0) * x0 / (reached.x - x0)));
            break;
        }
        base.push((reached.x, stress));
        previous = current;
    }
    let (mut load, mut area) = (0.0, 0.0);
    for pair in base.windows(2) {
        let ((x0, s0), (x1, s1)) = (pair[0], pair[1]);
        let width = x0 - x1;
        if soil.axisymmetric {
            load += 0.5 * (s0 * x0 + s1 * x1) * width;
            area += 0.5 * (x0 + x1) * width;
        } else {
            load += 0.5 * (s0 + s1) * width;
            area += width;
        }
    }
    load / area
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::footing::prandtl_nq;

    /// In plane strain the net reproduces Prandtl's closed form, within its
    /// second-order discretisation error (4e-4 at 40° with 60 rays), fifty
    /// times finer than the 5% the engine's footings are judged at.
    #[test]
    fn the_strip_gives_prandtls_nq() {
        for phi in [20.0, 32.0, 40.0] {
            let net = smooth_footing_nq(phi, Geometry::PlaneStrain, 60);
            let exact = prandtl_nq(phi);
            assert!(
                (net / exact - 1.0).abs() < 1e-3,
                "{phi}: {net} against {exact}"
            );
        }
    }

    /// As φ → 0 the circle's N_c = (N_q − 1) cot φ (Caquot's corresponding
    /// states) tends to Shield's (1955) 5.69 for a smooth circular punch on a
    /// Tresca soil; the strip's to Prandtl's 2 + π. N_c is linear in φ near
    /// zero, so two small angles extrapolate to φ = 0.
    #[test]
    fn the_circle_tends_to_shields_punch() {
        let n_c = |phi: Real, geometry| {
            (smooth_footing_nq(phi, geometry, 40) - 1.0) / phi.to_radians().tan()
        };
        let at_zero = |geometry| 2.0 * n_c(0.1, geometry) - n_c(0.2, geometry);
        let circle = at_zero(Geometry::Axisymmetric);
        let strip = at_zero(Geometry::PlaneStrain);
        assert!((circle - 5.69).abs() < 0.01, "{circle}");
        assert!(
            (strip - (2.0 + std::f64::consts::PI)).abs() < 0.005,
            "{strip}"
        );
    }

    /// The circle's N_q is converged in the net's fineness.
    #[test]
    fn the_circle_converges_in_the_net() {
        let coarse = smooth_footing_nq(32.0, Geometry::Axisymmetric, 30);
        let fine = smooth_footing_nq(32.0, Geometry::Axisymmetric, 60);
        println!("circle, 32°: N_q = {coarse:.3} (30 rays), {fine:.3} (60 rays)");
        assert!(
            (coarse / fine - 1.0).abs() < 1e-3,
            "{coarse} against {fine}"
        );
    }
}
