//! Key paths into a scene's dict: `materials[0].model.DruckerPrager.friction_angle`,
//! or with an entry's name, `materials[sand].density`.

use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// One step of a key path.
#[derive(Clone, Debug, PartialEq)]
enum Key {
    /// A dict's key.
    Field(String),
    /// A list's item by position.
    Index(usize),
    /// A list's item by its `name`.
    Named(String),
}

impl std::fmt::Display for Key {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Key::Field(name) => write!(f, ".{name}"),
            Key::Index(index) => write!(f, "[{index}]"),
            Key::Named(name) => write!(f, "[{name}]"),
        }
    }
}

/// A parsed key path.
pub struct KeyPath(Vec<Key>);

impl KeyPath {
    /// Parses `a.b[2].c`, `a[name].c` or `a["name.with.dots"].c`: in
    /// brackets, digits are a position and anything else a name (quoted,
    /// a name in any case).
    pub fn parse(text: &str) -> PyResult<Self> {
        let bad = || {
            PyValueError::new_err(format!(
                "not a key path: {text:?} (expected e.g. \"materials[0].model.DruckerPrager.friction_angle\" or \"materials[sand].density\")"
            ))
        };
        let mut keys = Vec::new();
        let mut rest = text;
        while !rest.is_empty() {
            if let Some(inner) = rest.strip_prefix('[') {
                let (key, after) = match inner.chars().next() {
                    Some(quote @ ('"' | '\'')) => {
                        let body = &inner[1..];
                        let end = body.find(quote).ok_or_else(bad)?;
                        let after = body[end + 1..].strip_prefix(']').ok_or_else(bad)?;
                        if end == 0 {
                            return Err(bad());
                        }
                        (Key::Named(body[..end].to_owned()), after)
                    }
                    _ => {
                        let end = inner.find(']').ok_or_else(bad)?;
                        let item = inner[..end].trim();
                        let key = match item.parse() {
                            Ok(index) => Key::Index(index),
                            Err(_) if !item.is_empty() => Key::Named(item.to_owned()),
                            Err(_) => return Err(bad()),
                        };
                        (key, &inner[end + 1..])
                    }
                };
                keys.push(key);
                rest = after;
            } else {
                let end = rest.find(['.', '[']).unwrap_or(rest.len());
                let field = &rest[..end];
                if field.is_empty() || field.contains(']') {
                    return Err(bad());
                }
                keys.push(Key::Field(field.to_owned()));
                rest = &rest[end..];
            }
            // Next: a bracket, the end, or a dot and a field.
            if let Some(after) = rest.strip_prefix('.') {
                if after.is_empty() || after.starts_with(['.', '[']) {
                    return Err(bad());
                }
                rest = after;
            } else if !rest.is_empty() && !rest.starts_with('[') {
                return Err(bad());
            }
        }
        if keys.is_empty() {
            return Err(bad());
        }
        Ok(Self(keys))
    }

    /// The value the path leads to in `root`.
    pub fn get<'py>(&self, root: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        self.0
            .iter()
            .try_fold(root.clone(), |node, key| step(&node, key))
    }

    /// Sets the value the path leads to in `root` (a dict's key may be new).
    pub fn set(&self, root: &Bound<'_, PyAny>, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let (last, parents) = self.0.split_last().expect("a key path has a key");
        let parent = parents
            .iter()
            .try_fold(root.clone(), |node, key| step(&node, key))?;
        match last {
            Key::Field(name) => parent.set_item(name, value),
            _ => {
                let index = list_index(&parent, last)?;
                parent.set_item(index, value)
            }
        }
    }
}

/// The item `key` selects in `node`.
fn step<'py>(node: &Bound<'py, PyAny>, key: &Key) -> PyResult<Bound<'py, PyAny>> {
    match key {
        Key::Field(name) => node
            .cast::<PyDict>()
            .ok()
            .and_then(|d| d.get_item(name).ok().flatten())
            .ok_or_else(|| PyKeyError::new_err(format!("no key {name:?} here"))),
        _ => node.get_item(list_index(node, key)?),
    }
}

/// The position in the list `node` that `key` selects.
fn list_index(node: &Bound<'_, PyAny>, key: &Key) -> PyResult<usize> {
    let list = node
        .cast::<PyList>()
        .map_err(|_| PyKeyError::new_err(format!("{key}: not a list here")))?;
    match key {
        Key::Index(index) if *index < list.len() => Ok(*index),
        Key::Index(index) => Err(PyKeyError::new_err(format!(
            "index {index} past the list's {} items",
            list.len()
        ))),
        Key::Named(name) => list
            .iter()
            .position(|item| name_of(&item).as_deref() == Some(name.as_str()))
            .ok_or_else(|| PyKeyError::new_err(format!("no entry named {name:?}"))),
        Key::Field(name) => Err(PyKeyError::new_err(format!("{name:?}: a list has no keys"))),
    }
}

/// An entry's `name`, if it is a dict with a string name.
fn name_of(item: &Bound<'_, PyAny>) -> Option<String> {
    let item = item.cast::<PyDict>().ok()?;
    item.get_item("name").ok()??.extract().ok()
}

/// The key path, in `scene`'s dict, of what the engine's error anchors
/// name (a section, an entry's quoted name, then field names, each found
/// below the one before): `None` without anchors.
pub fn place_of_anchors(scene: &Bound<'_, PyAny>, anchors: &[String]) -> Option<String> {
    let (section, rest) = anchors.split_first()?;
    let mut path = section.clone();
    let mut node = step(scene, &Key::Field(section.clone())).ok()?;
    for anchor in rest {
        if let Some(name) = anchor.strip_prefix('"').and_then(|a| a.strip_suffix('"')) {
            let key = Key::Named(name.to_owned());
            match list_index(&node, &key) {
                Ok(index) => {
                    path.push_str(&format!("[{index}]"));
                    node = node.get_item(index).ok()?;
                }
                Err(_) => break,
            }
        } else {
            match find_below(&node, anchor) {
                Some((below, found)) => {
                    path.push_str(&below);
                    node = found;
                }
                None => break,
            }
        }
    }
    Some(path)
}

/// The first key `name` at or below `node` (depth first, in order), with
/// the path to it from `node`.
fn find_below<'py>(node: &Bound<'py, PyAny>, name: &str) -> Option<(String, Bound<'py, PyAny>)> {
    if let Ok(dict) = node.cast::<PyDict>() {
        if let Some(value) = dict.get_item(name).ok().flatten() {
            return Some((format!(".{name}"), value));
        }
        for (key, value) in dict.iter() {
            if let Some((below, found)) = find_below(&value, name) {
                return Some((format!(".{key}{below}"), found));
            }
        }
    } else if let Ok(list) = node.cast::<PyList>() {
        for (index, item) in list.iter().enumerate() {
            if let Some((below, found)) = find_below(&item, name) {
                return Some((format!("[{index}]{below}"), found));
            }
        }
    }
    None
}
