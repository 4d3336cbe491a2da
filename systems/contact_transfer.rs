//! Algorithm 1, line 10: contact forces to the grid (paper section 3.2.3).

use crate::components::{
    BlockContacts, BlockId, BodyIndex, GridLayer, MaterialPoints, sort_into_scene_order,
};
use crate::contact::{ForceApplication, traction_points};
use crate::math::{DVec2, Real};
use crate::resources::{BodyContacts, ContactSettings, Grid};
use bevy_ecs::prelude::*;

/// In `Traction` mode, splits every contact force over the integration
/// points of the contact edge of the point's domain and adds each share to
/// the body's layer with the hat functions N_i (eq. 7b's traction term).
/// Contacts are visited in block order, then in each block's contact order,
/// then the body–body contacts in key order (each pair's two forces), so
/// the nodal sums are formed in a fixed order. In `BodyForce` mode the
/// particle-to-grid transfer maps `MaterialPoints::contact_force` with S_ip
/// instead, and this system does nothing.
///
/// Reads: `Grid`, `ContactSettings`, `BlockContacts`, `BodyContacts`, `MaterialPoints` (position, half-size).
/// Writes: `GridLayer::nodes` (external force).
pub fn transfer_contact_forces(
    grid: Res<Grid>,
    settings: Res<ContactSettings>,
    mut order: Local<Vec<(u32, Entity)>>,
    blocks: Query<(Entity, &BlockId, &BlockContacts)>,
    body_contacts: Res<BodyContacts>,
    mut body_order: Local<Vec<(BodyIndex, Entity)>>,
    mut bodies: Query<(Entity, &BodyIndex, &MaterialPoints, &mut GridLayer)>,
) {
    let ForceApplication::Traction { points: count } = settings.force_application else {
        return;
    };
    // Scenes are validated to at least 1; a system changing the setting at
    // run time must not make the split divide by zero.
    let count = count.max(1);
    sort_into_scene_order(&mut order, blocks.iter().map(|(e, id, _)| (id.index, e)));
    for (_, entity) in order.iter() {
        let Ok((_, _, contacts)) = blocks.get(*entity) else {
            continue;
        };
        for contact in &contacts.current {
            if let Ok((_, _, points, mut layer)) = bodies.get_mut(contact.body) {
                add_traction(
                    &grid,
                    points,
                    &mut layer,
                    contact.point,
                    contact.force,
                    count,
                );
            }
        }
    }
    if body_contacts.current.is_empty() {
        return;
    }
    sort_into_scene_order(&mut body_order, bodies.iter().map(|(e, i, ..)| (*i, e)));
    for contact in &body_contacts.current {
        for (body, point, force) in [
            (contact.a, contact.p, contact.force),
            (contact.b, contact.q, -contact.force),
        ] {
            if let Ok((_, _, points, mut layer)) = bodies.get_mut(body_order[body as usize].1) {
                add_traction(&grid, points, &mut layer, point, force, count);
            }
        }
    }
}

/// Splits `force` on point `p` over `count` points of the contact edge of
/// its domain (facing the force's direction) and adds each share to the
/// layer with the hat functions.
fn add_traction(
    grid: &Grid,
    points: &MaterialPoints,
    layer: &mut GridLayer,
    p: u32,
    force: DVec2,
    count: u32,
) {
    let magnitude = force.length();
    if magnitude == 0.0 {
        return;
    }
    let p = p as usize;
    let direction = force / magnitude;
    let share = force / count as Real;
    // uGIMP domains are square: the x half-size is the half-size.
    for at in traction_points(points.position[p], points.half_size[p].x, direction, count) {
        add_with_hat_functions(grid, layer, at, share);
    }
}

/// Adds `force` to the four nodes of the cell holding `at`, weighted by the
/// bilinear hat functions (a partition of unity, so the whole force arrives).
fn add_with_hat_functions(grid: &Grid, layer: &mut GridLayer, at: DVec2, force: DVec2) {
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
