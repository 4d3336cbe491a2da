//! The engine's built-in plugins as a group a user can change: a plugin
//! disabled, or replaced by one of the user's in the same place of the
//! build order.

use super::{
    BodyContactPlugin, CorePlugin, FrontsPlugin, MpmPlugin, RecordsPlugin, RigidBlocksPlugin,
    StagesPlugin,
};
use std::any::TypeId;

/// The built-in plugins in the order they are built: [`CorePlugin`],
/// [`RecordsPlugin`], [`FrontsPlugin`], [`RigidBlocksPlugin`],
/// [`BodyContactPlugin`], [`StagesPlugin`] (a plugin may use the resources
/// of those before it; stages come last, as entering the first stage
/// changes what the others set up). [`crate::Simulation::with_plugins`]
/// builds a scene with them.
///
/// ```
/// use mpdem::plugins::{DefaultPlugins, FrontsPlugin, RecordsPlugin};
///
/// let plugins = DefaultPlugins::default()
///     .disable::<FrontsPlugin>()
///     .replace::<RecordsPlugin>(RecordsPlugin);
/// assert_eq!(plugins.len(), 5);
/// ```
pub struct DefaultPlugins {
    /// Each plugin, with the type of the built-in plugin whose place it
    /// holds (its own type, unless it replaced one).
    plugins: Vec<(TypeId, Box<dyn MpmPlugin>)>,
}

impl Default for DefaultPlugins {
    fn default() -> Self {
        let mut group = Self {
            plugins: Vec::new(),
        };
        group.push(CorePlugin);
        group.push(RecordsPlugin);
        group.push(FrontsPlugin);
        group.push(RigidBlocksPlugin);
        group.push(BodyContactPlugin);
        group.push(StagesPlugin);
        group
    }
}

impl DefaultPlugins {
    fn push<P: MpmPlugin>(&mut self, plugin: P) {
        self.plugins.push((TypeId::of::<P>(), Box::new(plugin)));
    }

    fn position<P: MpmPlugin>(&self, doing: &str) -> usize {
        self.plugins
            .iter()
            .position(|(id, _)| *id == TypeId::of::<P>())
            .unwrap_or_else(|| {
                panic!(
                    "cannot {doing} {}: it is not in the group",
                    std::any::type_name::<P>()
                )
            })
    }

    /// The group without the plugin `P`: its feature is not set up and its
    /// systems are not in the step. [`CorePlugin`] holds the step itself;
    /// a simulation built without it is refused.
    ///
    /// # Panics
    /// If `P` is not in the group (disabled already, or not built in).
    pub fn disable<P: MpmPlugin>(mut self) -> Self {
        let at = self.position::<P>("disable");
        self.plugins.remove(at);
        self
    }

    /// The group with `with` built in the place of the plugin `P`. The
    /// simulation counts `P` as added: adding it again is refused.
    ///
    /// # Panics
    /// If `P` is not in the group.
    pub fn replace<P: MpmPlugin>(mut self, with: impl MpmPlugin) -> Self {
        let at = self.position::<P>("replace");
        self.plugins[at].1 = Box::new(with);
        self
    }

    /// The number of plugins in the group.
    pub fn len(&self) -> usize {
        self.plugins.len()
    }

    /// Whether the group holds no plugin.
    pub fn is_empty(&self) -> bool {
        self.plugins.is_empty()
    }

    /// Whether the place of the built-in plugin `P` is in the group (held
    /// by `P` or by its replacement).
    pub fn contains<P: MpmPlugin>(&self) -> bool {
        self.plugins.iter().any(|(id, _)| *id == TypeId::of::<P>())
    }

    /// The plugins in build order, each with the type of the built-in
    /// plugin whose place it holds.
    pub(crate) fn iter(&self) -> impl Iterator<Item = (TypeId, &dyn MpmPlugin)> {
        self.plugins.iter().map(|(id, p)| (*id, p.as_ref()))
    }
}
