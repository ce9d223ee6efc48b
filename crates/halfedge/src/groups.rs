//! What an OBJ file says about its faces besides their corners: materials (`usemtl`, with the
//! `mtllib` lines that name their files), objects (`o`), groups (`g`) and smoothing groups
//! (`s`), carried per face ([`FaceGroups`]) through subdivision and written back.
//!
//! A statement holds for the faces after it until the next statement of its kind. The values
//! are kept as the file writes them (the words after the keyword, joined by one space), so a
//! written file says what the read one said. Each face has a *class*: the combination of its
//! four values, one `u32` per face, the distinct combinations stored once. A subdivided level
//! gets its faces' classes from their base faces ([`FaceGroups::of_base_faces`], OpenSubdiv's
//! `InterpolateFaceUniform`), 4 bytes per face.
//!
//! ```
//! let text = "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
//!             o box\nusemtl red\nf 1 2 3\nusemtl blue\ng sides\nf 1 3 4\n";
//! let mesh = halfedge::io::read_obj_from(text.as_bytes(), "box.obj")?;
//! let groups = mesh.groups().expect("the file has materials");
//! use halfedge::groups::Statement;
//! assert_eq!(groups.mtllib(), ["mtllib a.mtl"]);
//! assert_eq!(groups.value(0, Statement::Material), Some("red"));
//! assert_eq!(groups.value(1, Statement::Material), Some("blue"));
//! assert_eq!(groups.value(0, Statement::Group), None);
//! assert_eq!(groups.value(1, Statement::Object), Some("box"));
//!
//! // Four faces from face 1, two from face 0 (a subdivided level's base faces).
//! let level = groups.of_base_faces(vec![1, 1, 0, 0, 1, 1])?;
//! assert_eq!(level.value(2, Statement::Material), Some("red"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::collections::HashMap;

/// One of the statements [`FaceGroups`] carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Statement {
    /// `o NAME`: the object.
    Object,
    /// `g NAME...`: the groups.
    Group,
    /// `usemtl NAME`: the material.
    Material,
    /// `s N` or `s off`: the smoothing group.
    Smoothing,
}

impl Statement {
    /// Every statement, in the order the writers put them before a face.
    pub const ALL: [Statement; 4] = [
        Statement::Object,
        Statement::Group,
        Statement::Material,
        Statement::Smoothing,
    ];

    /// The OBJ keyword.
    pub fn keyword(self) -> &'static str {
        match self {
            Statement::Object => "o",
            Statement::Group => "g",
            Statement::Material => "usemtl",
            Statement::Smoothing => "s",
        }
    }

    /// What a writer puts for a face without this statement after a face with one (its
    /// file had none before its first face of the kind; OBJ's defaults, `default` where
    /// OBJ has none).
    pub fn unset(self) -> &'static str {
        match self {
            Statement::Smoothing => "off",
            _ => "default",
        }
    }

    fn index(self) -> usize {
        self as usize
    }

    /// The statement of an OBJ keyword.
    pub fn of_keyword(keyword: &str) -> Option<Statement> {
        Statement::ALL.into_iter().find(|s| s.keyword() == keyword)
    }
}

/// No value: the face comes before the first statement of its kind.
const NONE: u32 = u32::MAX;

/// The `mtllib`, `usemtl`, `o`, `g` and `s` statements of a face list, per face (module
/// docs).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FaceGroups {
    /// The `mtllib` lines, verbatim, in file order.
    mtllib: Vec<String>,
    /// Per statement, its distinct values in order of first appearance.
    values: [Vec<String>; 4],
    /// The distinct combinations of values (an index into `values` per statement, or `NONE`).
    classes: Vec<[u32; 4]>,
    /// The class of each face.
    faces: Vec<u32>,
}

/// Groups that do not fit their faces.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum GroupsError {
    /// A face index beyond the groups' faces.
    #[error("face {face} has no groups: there are {count} faces")]
    FaceOutOfRange {
        /// The face asked for.
        face: u64,
        /// The faces the groups have.
        count: usize,
    },
    /// Groups of another number of faces than the mesh's.
    #[error("groups of {given} faces for a mesh with {expected} faces")]
    FaceCount {
        /// Faces of the groups.
        given: usize,
        /// Faces of the mesh.
        expected: usize,
    },
}

impl FaceGroups {
    /// Groups of no face yet, with these `mtllib` lines (written verbatim before the first
    /// `v`); faces are added with [`push_face`](Self::push_face).
    ///
    /// ```
    /// use halfedge::groups::{FaceGroups, Statement};
    /// let mut groups = FaceGroups::new(vec!["mtllib scene.mtl".into()]);
    /// groups.push_face([None, Some("body"), Some("red"), None]);
    /// groups.push_face([None, Some("body"), Some("blue"), None]);
    /// assert_eq!(groups.values(Statement::Material), ["red", "blue"]);
    /// assert_eq!(groups.value_index(1, Statement::Material), Some(1));
    /// ```
    pub fn new(mtllib: Vec<String>) -> FaceGroups {
        FaceGroups {
            mtllib,
            classes: vec![[NONE; 4]],
            ..FaceGroups::default()
        }
    }

    /// Appends a face with its values, one per statement in the order of [`Statement::ALL`]
    /// (object, group, material, smoothing), `None` for none. Linear in the distinct values
    /// and classes so far (a builder for a handful of materials; the reader hashes).
    pub fn push_face(&mut self, values: [Option<&str>; 4]) {
        let mut class = [NONE; 4];
        for (i, value) in values.iter().enumerate() {
            if let Some(value) = value {
                let list = &mut self.values[i];
                class[i] = match list.iter().position(|v| v == value) {
                    Some(k) => k as u32,
                    None => {
                        list.push((*value).to_string());
                        list.len() as u32 - 1
                    }
                };
            }
        }
        let id = match self.classes.iter().position(|c| *c == class) {
            Some(k) => k as u32,
            None => {
                self.classes.push(class);
                self.classes.len() as u32 - 1
            }
        };
        self.faces.push(id);
    }

    /// The distinct values of `statement`, in order of first appearance (the materials of a
    /// mesh, say: one draw call each).
    pub fn values(&self, statement: Statement) -> &[String] {
        &self.values[statement.index()]
    }

    /// The index of face `face`'s value of `statement` in [`values`](Self::values), `None`
    /// when it has none or is not a face of these groups.
    pub fn value_index(&self, face: usize, statement: Statement) -> Option<u32> {
        let class = self.classes[*self.faces.get(face)? as usize];
        Some(class[statement.index()]).filter(|&v| v != NONE)
    }

    /// The `mtllib` lines of the file, verbatim, in file order.
    pub fn mtllib(&self) -> &[String] {
        &self.mtllib
    }

    /// The number of faces.
    pub fn n_faces(&self) -> usize {
        self.faces.len()
    }

    /// The value of `statement` for face `face` (the words after the keyword), `None` when
    /// the face comes before the first such statement or is not a face of these groups.
    pub fn value(&self, face: usize, statement: Statement) -> Option<&str> {
        let class = self.classes[*self.faces.get(face)? as usize];
        let v = class[statement.index()];
        (v != NONE).then(|| self.values[statement.index()][v as usize].as_str())
    }

    /// The class of face `face`: faces of one class have the same four values.
    pub fn class(&self, face: usize) -> Option<u32> {
        self.faces.get(face).copied()
    }

    /// Whether two classes differ in `statement`, and the value of the second (`None`: the
    /// statement's [`Statement::unset`] value).
    pub(crate) fn change(
        &self,
        before: Option<u32>,
        class: u32,
        statement: Statement,
    ) -> Option<Option<&str>> {
        let i = statement.index();
        let now = self.classes[class as usize][i];
        let was = before.map(|b| self.classes[b as usize][i]);
        if was == Some(now) || (was.is_none() && now == NONE) {
            return None;
        }
        Some((now != NONE).then(|| self.values[i][now as usize].as_str()))
    }

    /// The groups of a level whose face `i` comes from face `base[i]` of these (what
    /// [`Refinement::base_faces`](crate::Refinement::base_faces) and
    /// [`FaceListLevel::base_faces`](crate::subdivide::FaceListLevel::base_faces) give): the
    /// `base` vector becomes the level's classes, so this allocates no per-face memory.
    ///
    /// # Errors
    ///
    /// [`GroupsError`] for an index that is not a face of these groups.
    pub fn of_base_faces(&self, mut base: Vec<u32>) -> Result<FaceGroups, GroupsError> {
        for f in base.iter_mut() {
            *f = *self
                .faces
                .get(*f as usize)
                .ok_or(GroupsError::FaceOutOfRange {
                    face: u64::from(*f),
                    count: self.faces.len(),
                })?;
        }
        Ok(FaceGroups {
            mtllib: self.mtllib.clone(),
            values: self.values.clone(),
            classes: self.classes.clone(),
            faces: base,
        })
    }

    /// The bytes the groups hold on the heap (the per-face classes and the strings).
    pub fn heap_bytes(&self) -> usize {
        let strings: usize = self
            .values
            .iter()
            .flatten()
            .chain(&self.mtllib)
            .map(|s| s.capacity() + std::mem::size_of::<String>())
            .sum();
        strings + 16 * self.classes.capacity() + 4 * self.faces.capacity()
    }
}

/// Builds [`FaceGroups`] while a file is read: the statements seen so far, the class of each
/// face pushed. Nothing is kept per face before the first statement (a file without any
/// costs nothing).
#[derive(Debug, Default)]
pub(crate) struct GroupsReader {
    groups: FaceGroups,
    /// The values of the statements read so far.
    current: [u32; 4],
    /// The faces read before the first statement.
    before: usize,
    /// The index of each value, per statement, and of each class.
    value_ids: [HashMap<String, u32>; 4],
    class_ids: HashMap<[u32; 4], u32>,
    /// Whether any statement was read (else there are no groups).
    any: bool,
}

impl GroupsReader {
    /// Records an `mtllib` line (its text after comments, trimmed).
    pub(crate) fn mtllib(&mut self, line: &str) -> Result<(), std::collections::TryReserveError> {
        self.start();
        self.groups.mtllib.try_reserve(1)?;
        let mut text = String::new();
        text.try_reserve_exact(line.len())?;
        text.push_str(line);
        self.groups.mtllib.push(text);
        Ok(())
    }

    /// The first statement: the faces before it get the class of no value.
    fn start(&mut self) {
        if !self.any {
            self.any = true;
            self.current = [NONE; 4];
            self.groups.classes.push(self.current);
            self.class_ids.insert(self.current, 0);
            self.groups.faces = vec![0; self.before];
        }
    }

    /// Records a statement with the words after its keyword.
    pub(crate) fn statement<'a>(
        &mut self,
        statement: Statement,
        words: impl Iterator<Item = &'a str>,
    ) {
        self.start();
        let value = words.collect::<Vec<_>>().join(" ");
        let i = statement.index();
        let ids = &mut self.value_ids[i];
        let values = &mut self.groups.values[i];
        let id = *ids.entry(value).or_insert_with_key(|v| {
            values.push(v.clone());
            values.len() as u32 - 1
        });
        self.current[i] = id;
    }

    /// Records the next face, under the statements read so far.
    pub(crate) fn face(&mut self) -> Result<(), std::collections::TryReserveError> {
        if !self.any {
            self.before += 1;
            return Ok(());
        }
        let classes = &mut self.groups.classes;
        let class = *self.class_ids.entry(self.current).or_insert_with(|| {
            classes.push(self.current);
            classes.len() as u32 - 1
        });
        self.groups.faces.try_reserve(1)?;
        self.groups.faces.push(class);
        Ok(())
    }

    /// The bytes held so far.
    pub(crate) fn heap_bytes(&self) -> usize {
        let keys: usize = self
            .value_ids
            .iter()
            .flatten()
            .map(|(k, _)| k.capacity() + 48)
            .sum();
        self.groups.heap_bytes() + 24 * self.class_ids.capacity() + keys
    }

    /// The groups, `None` when the file had no statement of the five kinds.
    pub(crate) fn finish(self) -> Option<FaceGroups> {
        self.any.then_some(self.groups)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_are_shared_and_changes_are_per_statement() {
        let mut r = GroupsReader::default();
        r.face().expect("room");
        r.statement(Statement::Material, ["red"].into_iter());
        r.face().expect("room");
        r.statement(Statement::Group, ["a", "b"].into_iter());
        r.face().expect("room");
        r.statement(Statement::Material, ["red"].into_iter());
        r.face().expect("room");
        let g = r.finish().expect("statements");
        assert_eq!(g.n_faces(), 4);
        assert_eq!(g.classes.len(), 3);
        assert_eq!(g.class(2), g.class(3));
        assert_eq!(g.class(0), Some(0));
        assert_eq!(g.value(0, Statement::Material), None);
        assert_eq!(g.value(2, Statement::Group), Some("a b"));
        let (c0, c1, c2) = (0, 1, 2);
        assert_eq!(g.change(None, c0, Statement::Material), None);
        assert_eq!(
            g.change(Some(c0), c1, Statement::Material),
            Some(Some("red"))
        );
        assert_eq!(g.change(Some(c1), c2, Statement::Material), None);
        assert_eq!(g.change(Some(c2), c0, Statement::Group), Some(None));
        let level = g.of_base_faces(vec![3, 0]).expect("faces");
        assert_eq!(level.value(0, Statement::Group), Some("a b"));
        let err = g.of_base_faces(vec![4]).unwrap_err();
        assert_eq!(err.to_string(), "face 4 has no groups: there are 4 faces");
        assert!(GroupsReader::default().finish().is_none());
    }
}
