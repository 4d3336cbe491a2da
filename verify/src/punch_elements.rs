//! The axisymmetric punch by finite elements: a reference independent of
//! the material point method and of the DEM contact.
//!
//! A rigid, frictionless flat punch of radius a is pressed into an elastic
//! cylinder of radius L and height H: the base is fixed, the outer wall
//! r = L a roller (u_r = 0), the axis holds u_r = 0, and the top is free
//! outside the punch. Under the punch the top nodes (r ≤ a) take the
//! punch's displacement u_z = −1 and slide freely in r. The mesh is square
//! bilinear (Q4) elements of side a/n with 2 × 2 Gauss points, axisymmetric
//! small strain (ε_rr, ε_zz, ε_θθ = u_r / r, γ_rz) integrated with the
//! weight 2π r. The static problem is solved by conjugate gradients with a
//! diagonal preconditioner; the punch's stiffness is the sum of the
//! reactions at its nodes.
//!
//! The stress under a rigid punch's edge is singular (as (a − r)^(−1/2)),
//! so the elements' stiffness converges at first order in a/n, from above.

use super::quad4::{gauss_points, local_gradients, shape};
use mpdem::math::Real;
use std::f64::consts::PI;

/// The punch, the cylinder and its material.
#[derive(Clone, Copy, Debug)]
pub struct PunchCylinder {
    /// Punch radius a (m).
    pub punch_radius: Real,
    /// Cylinder radius L (m), a whole number of a/n.
    pub radius: Real,
    /// Cylinder height H (m), a whole number of a/n.
    pub height: Real,
    /// Young's modulus (Pa).
    pub youngs_modulus: Real,
    /// Poisson's ratio.
    pub poisson_ratio: Real,
}

/// An element's stiffness, its eight degrees of freedom (u_r, u_z of the
/// nodes counter-clockwise from the lower left).
type ElementMatrix = [[Real; 8]; 8];

/// The mesh: nodes (i, j) at (i s, j s), numbered i (nz + 1) + j.
struct Mesh {
    nr: usize,
    nz: usize,
    /// Stiffness of the elements of column i (they depend on r only).
    columns: Vec<ElementMatrix>,
}

impl Mesh {
    fn node(&self, i: usize, j: usize) -> usize {
        i * (self.nz + 1) + j
    }

    fn dofs(&self) -> usize {
        2 * (self.nr + 1) * (self.nz + 1)
    }

    /// The degrees of freedom of element (i, j).
    fn element_dofs(&self, i: usize, j: usize) -> [usize; 8] {
        let nodes = [
            self.node(i, j),
            self.node(i + 1, j),
            self.node(i + 1, j + 1),
            self.node(i, j + 1),
        ];
        std::array::from_fn(|k| 2 * nodes[k / 2] + k % 2)
    }

    /// y = K x.
    fn apply(&self, x: &[Real], y: &mut [Real]) {
        y.fill(0.0);
        for i in 0..self.nr {
            let k = &self.columns[i];
            for j in 0..self.nz {
                let dofs = self.element_dofs(i, j);
                let xe = dofs.map(|d| x[d]);
                for (row, &d) in k.iter().zip(&dofs) {
                    y[d] += row.iter().zip(&xe).map(|(a, b)| a * b).sum::<Real>();
                }
            }
        }
    }

    /// The diagonal of K.
    fn diagonal(&self) -> Vec<Real> {
        let mut diagonal = vec![0.0; self.dofs()];
        for i in 0..self.nr {
            for j in 0..self.nz {
                for (k, d) in self.element_dofs(i, j).into_iter().enumerate() {
                    diagonal[d] += self.columns[i][k][k];
                }
            }
        }
        diagonal
    }
}

impl PunchCylinder {
    /// The stiffness F/δ of the punch (N/m, F its whole force) on square
    /// elements of side a / `elements_per_radius`.
    pub fn stiffness(&self, elements_per_radius: usize) -> Real {
        let side = self.punch_radius / elements_per_radius as Real;
        let count = |length: Real| {
            let n = (length / side).round();
            assert!(
                (n * side - length).abs() < 1e-9 * length,
                "the cylinder must be a whole number of elements"
            );
            n as usize
        };
        let (nr, nz) = (count(self.radius), count(self.height));
        let mesh = Mesh {
            nr,
            nz,
            columns: (0..nr).map(|i| self.element_matrix(i, side)).collect(),
        };
        let n = mesh.dofs();
        let mut fixed = vec![false; n];
        let mut prescribed = vec![0.0; n];
        for j in 0..=nz {
            fixed[2 * mesh.node(0, j)] = true;
            fixed[2 * mesh.node(nr, j)] = true;
        }
        for i in 0..=nr {
            fixed[2 * mesh.node(i, 0)] = true;
            fixed[2 * mesh.node(i, 0) + 1] = true;
        }
        let under_punch: Vec<usize> = (0..=elements_per_radius)
            .map(|i| 2 * mesh.node(i, nz) + 1)
            .collect();
        for &d in &under_punch {
            fixed[d] = true;
            prescribed[d] = -1.0;
        }
        let u = solve(&mesh, &fixed, &prescribed);
        let mut reaction = vec![0.0; n];
        mesh.apply(&u, &mut reaction);
        -under_punch.iter().map(|&d| reaction[d]).sum::<Real>()
    }

    /// The stiffness of an element of column i (r from i s to (i + 1) s).
    fn element_matrix(&self, column: usize, side: Real) -> ElementMatrix {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
        // Strains (rr, zz, θθ, rz) to stresses.
        let d = [
            [c * (1.0 - nu), c * nu, c * nu, 0.0],
            [c * nu, c * (1.0 - nu), c * nu, 0.0],
            [c * nu, c * nu, c * (1.0 - nu), 0.0],
            [0.0, 0.0, 0.0, c * (1.0 - 2.0 * nu) / 2.0],
        ];
        let left = column as Real * side;
        let mut k = [[0.0; 8]; 8];
        for s in gauss_points() {
            let n = shape(s);
            let grad = local_gradients(s).map(|g| g * (2.0 / side));
            let r = left + 0.5 * side * (1.0 + s.x);
            let mut b = [[0.0; 8]; 4];
            for a in 0..4 {
                b[0][2 * a] = grad[a].x;
                b[1][2 * a + 1] = grad[a].y;
                b[2][2 * a] = n[a] / r;
                b[3][2 * a] = grad[a].y;
                b[3][2 * a + 1] = grad[a].x;
            }
            let weight = 2.0 * PI * r * (0.5 * side) * (0.5 * side);
            for p in 0..8 {
                for q in 0..8 {
                    let mut sum = 0.0;
                    for (x, dx) in d.iter().enumerate() {
                        for (y, dxy) in dx.iter().enumerate() {
                            sum += b[x][p] * dxy * b[y][q];
                        }
                    }
                    k[p][q] += sum * weight;
                }
            }
        }
        k
    }
}

/// The displacements with the `fixed` degrees of freedom at `prescribed`
/// and no force on the others: preconditioned conjugate gradients on the
/// free ones, to a residual of 1e-11 of the first.
fn solve(mesh: &Mesh, fixed: &[bool], prescribed: &[Real]) -> Vec<Real> {
    let n = mesh.dofs();
    let free = |v: &mut [Real]| {
        for (x, &f) in v.iter_mut().zip(fixed) {
            if f {
                *x = 0.0;
            }
        }
    };
    let inverse_diagonal: Vec<Real> = mesh.diagonal().iter().map(|d| 1.0 / d).collect();
    let mut residual = vec![0.0; n];
    mesh.apply(prescribed, &mut residual);
    residual.iter_mut().for_each(|r| *r = -*r);
    free(&mut residual);
    let dot = |a: &[Real], b: &[Real]| a.iter().zip(b).map(|(x, y)| x * y).sum::<Real>();
    let mut x = vec![0.0; n];
    let mut z: Vec<Real> = residual
        .iter()
        .zip(&inverse_diagonal)
        .map(|(r, m)| r * m)
        .collect();
    let mut p = z.clone();
    let mut kp = vec![0.0; n];
    let mut rz = dot(&residual, &z);
    let first = dot(&residual, &residual).sqrt();
    for _ in 0..20 * n {
        mesh.apply(&p, &mut kp);
        free(&mut kp);
        let alpha = rz / dot(&p, &kp);
        for k in 0..n {
            x[k] += alpha * p[k];
            residual[k] -= alpha * kp[k];
        }
        if dot(&residual, &residual).sqrt() <= 1e-11 * first {
            break;
        }
        for k in 0..n {
            z[k] = residual[k] * inverse_diagonal[k];
        }
        let rz_next = dot(&residual, &z);
        let beta = rz_next / rz;
        rz = rz_next;
        for k in 0..n {
            p[k] = z[k] + beta * p[k];
        }
    }
    for k in 0..n {
        if fixed[k] {
            x[k] = prescribed[k];
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A punch as wide as the cylinder compresses it in uniaxial strain
    /// between the roller wall and the fixed base: F/δ = M π L² / H with
    /// M = E (1 − ν) / ((1 + ν)(1 − 2ν)), which bilinear elements hold
    /// exactly (the field is linear).
    #[test]
    fn a_punch_as_wide_as_the_cylinder_compresses_it_in_uniaxial_strain() {
        let (e, nu) = (2.0, 0.3);
        let cylinder = PunchCylinder {
            punch_radius: 1.0,
            radius: 1.0,
            height: 2.0,
            youngs_modulus: e,
            poisson_ratio: nu,
        };
        let m = e * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let exact = m * PI / 2.0;
        let k = cylinder.stiffness(4);
        assert!((k / exact - 1.0).abs() < 1e-9, "{k} against {exact}");
    }

    /// Halving the elements halves the stiffness's excess (first order,
    /// the punch's edge singularity), as the reference's extrapolation
    /// assumes: the ratio of successive changes lies within 0.4–0.6.
    #[test]
    fn the_stiffness_converges_at_first_order() {
        let cylinder = PunchCylinder {
            punch_radius: 1.0,
            radius: 3.0,
            height: 3.0,
            youngs_modulus: 1.0,
            poisson_ratio: 0.3,
        };
        let k: Vec<Real> = [5, 10, 20].map(|n| cylinder.stiffness(n)).to_vec();
        let ratio = (k[1] - k[2]) / (k[0] - k[1]);
        assert!(k[0] > k[1] && k[1] > k[2], "{k:?}");
        assert!((0.4..0.6).contains(&ratio), "ratio {ratio}");
    }
}
