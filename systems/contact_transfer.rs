//! Algorithm 1, line 10: contact forces to the grid (paper section 3.2.3).

use crate::components::{
    BlockContacts, BlockId, BodyIndex, GridLayer, MaterialPoints, sort_into_scene_order,
};
use crate::contact::{ForceApplication, traction_points};
use crate::distributed::{ContactHalfSizes, PointIds, local_index};
use crate::math::{DVec2, Real, outer};
use crate::resources::{BodyContacts, ContactSettings, Grid, Settings};
use crate::shape_functions::{ShapeFunction, StencilGrid};
use bevy_ecs::prelude::*;

/// In `Traction` mode, splits every contact force over the integration
/// points of the contact edge of the point's domain (facing the contact's
/// normal) and adds each share to the body's layer with the hat functions
/// N_i (eq. 7b's traction term).
/// In `BodyForce` mode the particle-to-grid transfer maps
/// `MaterialPoints::contact_force` with S_ip, and this system adds the
/// tangential force's first moment about the point, (f_t ⊗ (x_c − x_p))
/// G_ip for f_t at the contact point x_c (the rest of S_i(x_c) f_t to first
/// order). The tangential force then acts where it touches: its moment
/// about the point reaches the body, and the material's rotation about the
/// point, which stretches the contact's tangential spring, is motion the
/// force does work on. The normal force, along the arm, has no moment; its
/// first moment would stretch the material along the normal, work its
/// spring (a potential of the centres) does not hold, so it stays at the
/// centre. Contacts are visited in block order, then in each block's
/// contact order, then the body–body contacts in key order (each pair's
/// two forces), so the nodal sums are formed in a fixed order.
///
/// In a distributed run every process holds every block contact: the
/// contacts of the points another process holds are added too, to the
/// nodes of this process's layer their stencils reach, so that the nodes
/// two processes share get every contact, in the one-process order.
///
/// Reads: `Grid`, `ContactSettings`, `Settings::shape_function`,
/// `BlockContacts`, `BodyContacts`, `MaterialPoints` (position, half-size).
/// Writes: `GridLayer::nodes` (external force).
#[allow(clippy::too_many_arguments)] // the distributed run's half-sizes are one more
pub fn transfer_contact_forces(
    (grid, settings, numerics): (Res<Grid>, Res<ContactSettings>, Res<Settings>),
    mut order: Local<Vec<(u32, Entity)>>,
    blocks: Query<(Entity, &BlockId, &BlockContacts)>,
    body_contacts: Option<Res<BodyContacts>>,
    mut body_order: Local<Vec<(BodyIndex, Entity)>>,
    mut bodies: Query<(Entity, &BodyIndex, &MaterialPoints, &mut GridLayer)>,
    (ids, half_sizes): (Query<&PointIds>, Option<Res<ContactHalfSizes>>),
) {
    let transfer = match settings.force_application {
        // Scenes are validated to at least 1; a system changing the setting
        // at run time must not make the split divide by zero.
        ForceApplication::Traction { points } => Transfer::Traction(points.max(1)),
        ForceApplication::BodyForce => {
            Transfer::Moment(numerics.shape_function, grid.stencil_grid())
        }
    };
    // `force` on the point at `place`, its tangential part `tangential`,
    // at `at`.
    let add = |place: PointPlace,
               layer: &mut GridLayer,
               (force, tangential, at): (DVec2, DVec2, DVec2)| {
        match &transfer {
            Transfer::Traction(count) => {
                add_traction(&grid, place, layer, (force, force - tangential), *count)
            }
            Transfer::Moment(kernel, stencil_grid) => {
                add_moment(*kernel, stencil_grid, place, layer, tangential, at)
            }
        }
    };
    sort_into_scene_order(&mut order, blocks.iter().map(|(e, id, _)| (id.index, e)));
    for (_, entity) in order.iter() {
        let Ok((_, id, contacts)) = blocks.get(*entity) else {
            continue;
        };
        for contact in &contacts.current {
            if let Ok((_, _, points, mut layer)) = bodies.get_mut(contact.body) {
                let place = match local_index(ids.get(contact.body).ok(), contact.point) {
                    Some(p) => PointPlace::Held(points.position[p], points.half_size[p]),
                    None => match half_sizes.as_ref().and_then(|h| h.of(id.index, contact)) {
                        Some(half_size) => PointPlace::Elsewhere(contact.from, half_size),
                        None => continue,
                    },
                };
                let acting = (contact.force, contact.tangential, contact.at);
                add(place, &mut layer, acting);
            }
        }
    }
    let Some(body_contacts) = body_contacts.filter(|c| !c.current.is_empty()) else {
        return;
    };
    sort_into_scene_order(&mut body_order, bodies.iter().map(|(e, i, ..)| (*i, e)));
    for contact in &body_contacts.current {
        for (body, point, sign) in [(contact.a, contact.p, 1.0), (contact.b, contact.q, -1.0)] {
            if let Ok((_, _, points, mut layer)) = bodies.get_mut(body_order[body as usize].1) {
                let p = point as usize;
                let place = PointPlace::Held(points.position[p], points.half_size[p]);
                let acting = (sign * contact.force, sign * contact.tangential, contact.at);
                add(place, &mut layer, acting);
            }
        }
    }
}

/// A contact's point: its position and domain half-size, and whether this
/// process holds it.
#[derive(Clone, Copy)]
enum PointPlace {
    /// One of this process's points: its stencil lies in the layer's window.
    Held(DVec2, DVec2),
    /// A point another process holds: its stencil may reach past the window.
    Elsewhere(DVec2, DVec2),
}

impl PointPlace {
    /// The point's position and domain half-size.
    fn position_and_half_size(self) -> (DVec2, DVec2) {
        match self {
            PointPlace::Held(x, h) | PointPlace::Elsewhere(x, h) => (x, h),
        }
    }
}

/// How the contact forces reach the grid in this system.
enum Transfer {
    /// Over this many points of the contact edge of the point's domain.
    Traction(u32),
    /// The tangential force's first moment about the point, with the
    /// body's stencils.
    Moment(ShapeFunction, StencilGrid),
}

/// Adds the first moment of `force` at `at` about the point at `place`,
/// (f ⊗ (x_c − x_p)) G_ip, to the nodes of the point's stencil (none for a
/// point that has left the grid, which particle-to-grid reports).
fn add_moment(
    kernel: ShapeFunction,
    stencil_grid: &StencilGrid,
    place: PointPlace,
    layer: &mut GridLayer,
    force: DVec2,
    at: DVec2,
) {
    let (position, half_size) = place.position_and_half_size();
    let Some(stencil) = kernel.stencil(position, half_size, stencil_grid) else {
        return;
    };
    let moment = outer(force, at - position);
    if let PointPlace::Elsewhere(..) = place {
        // Each node's share formed alone (−0 is the sum's identity, so a
        // node's share is the very term it gets on the point's process),
        // then added to the nodes inside the window.
        let mut shares = [DVec2::splat(-0.0); 9];
        stencil.scatter(&mut shares, stencil.base, 3, |share, _, g, _| {
            *share += moment * g;
        });
        for (k, share) in shares.iter().enumerate() {
            let node = [
                stencil.base[0] as usize + k % 3,
                stencil.base[1] as usize + k / 3,
            ];
            if let Some(node) = layer.node_mut(node) {
                node.external_force += *share;
            }
        }
        return;
    }
    let window = layer.window();
    let (origin, row_len) = (window.start.map(|k| k as u32), window.width());
    stencil.scatter(layer.nodes_mut(), origin, row_len, |node, _, g, _| {
        node.external_force += moment * g;
    });
}

/// Splits `force` on the point at `place` over `count` points of the
/// contact edge of its domain and adds each share to the layer with the hat functions. The
/// edge faces the contact: it is turned to the normal part `normal` of the
/// force (to the force itself where that part is zero), not to the force
/// as the paper turns it. Turned with a force that friction tilts, the
/// edge, and with it where the force acts on the body, swings as the
/// friction force changes, and a punch held still on a pad of one point
/// per cell (`tests/energy_balance.rs`) fed the pad 1.1 times the work that
/// pushed it in, in 0.2 s, against 0.9% turned to the normal.
fn add_traction(
    grid: &Grid,
    place: PointPlace,
    layer: &mut GridLayer,
    (force, normal): (DVec2, DVec2),
    count: u32,
) {
    let magnitude = force.length();
    if magnitude == 0.0 {
        return;
    }
    let (position, half_size) = place.position_and_half_size();
    // A contact's tangential force is at most μ times its normal force
    // (eq. 18b), so a force with no normal part is zero and has returned
    // above; the fallback only guards against a normal part lost to
    // round-off beside a huge μ.
    let direction = normal.try_normalize().unwrap_or(force / magnitude);
    let share = force / count as Real;
    // uGIMP domains are square: the x half-size is the half-size.
    for at in traction_points(position, half_size.x, direction, count) {
        add_with_hat_functions(grid, layer, at, share);
    }
}

/// Adds `force` to the four nodes of the cell holding `at`, weighted by the
/// bilinear hat functions (a partition of unity, so the whole force arrives).
pub(crate) fn add_with_hat_functions(grid: &Grid, layer: &mut GridLayer, at: DVec2, force: DVec2) {
    let [nx, ny] = grid.nodes();
    let s = (at - grid.origin) / grid.cell_size;
    let i = (s.x.floor().max(0.0) as usize).min(nx - 2);
    let j = (s.y.floor().max(0.0) as usize).min(ny - 2);
    let fx = (s.x - i as Real).clamp(0.0, 1.0);
    let fy = (s.y - j as Real).clamp(0.0, 1.0);
    let weights = [
        (0, 0, (1.0 - fx) * (1.0 - fy)),
        (1, 0, fx * (1.0 - fy)),
        (0, 1, (1.0 - fx) * fy),
        (1, 1, fx * fy),
    ];
    for (di, dj, w) in weights {
        // The cell is within the active nodes of a point inside the grid;
        // a point that has left the grid (reported by P2G) may miss them,
        // and its force is then dropped.
        if let Some(node) = layer.node_mut([i + di, j + dj]) {
            node.external_force += w * force;
        }
    }
}
