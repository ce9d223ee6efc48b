//! The PLY data: elements read in ASCII or binary, faces, colors and texture coordinates.

use std::collections::HashMap;
use std::io::BufRead;

use glam::{DVec2, DVec3};

use super::super::{shorten, Budget};
use super::binary::{Bytes, Layout};
use super::*;
use crate::error::{Error, ParseError, Result};
use crate::polygon::PolygonMesh;
use crate::uv::Uvs;

// ---------------------------------------------------------------------------------------
// The data.

/// The faces read so far: with the line of each (ASCII data: [`PolygonMesh::face_line`]), or
/// plain arrays (binary data has no lines).
pub(super) enum Faces {
    Lines(Box<PolygonMesh>),
    Plain {
        offsets: Vec<usize>,
        indices: Vec<u32>,
    },
}

impl Faces {
    pub(super) fn bytes(&self) -> usize {
        match self {
            Faces::Lines(mesh) => mesh.heap_bytes(),
            Faces::Plain { offsets, indices } => {
                std::mem::size_of_val(offsets.as_slice())
                    + std::mem::size_of_val(indices.as_slice())
            }
        }
    }

    pub(super) fn n_faces(&self) -> usize {
        match self {
            Faces::Lines(mesh) => mesh.n_faces(),
            Faces::Plain { offsets, .. } => offsets.len() - 1,
        }
    }

    pub(super) fn indices(&self) -> &[u32] {
        match self {
            Faces::Lines(mesh) => mesh.face_indices(),
            Faces::Plain { indices, .. } => indices,
        }
    }

    pub(super) fn push(
        &mut self,
        corners: &[u32],
        line: u64,
    ) -> std::result::Result<(), std::collections::TryReserveError> {
        match self {
            Faces::Lines(mesh) => mesh.try_push_face_from_line(corners, line),
            Faces::Plain { offsets, indices } => {
                offsets.try_reserve(1)?;
                indices.try_reserve(corners.len())?;
                indices.extend_from_slice(corners);
                offsets.push(indices.len());
                Ok(())
            }
        }
    }

    pub(super) fn into_mesh(self, positions: Vec<DVec3>) -> PolygonMesh {
        match self {
            Faces::Lines(mut mesh) => {
                mesh.positions = positions;
                *mesh
            }
            Faces::Plain { offsets, indices } => {
                PolygonMesh::from_raw_parts(positions, offsets, indices)
            }
        }
    }
}

/// Per-face texture coordinates: the distinct (bit-for-bit) `(vertex, u, v)` triples in order
/// of first appearance (a `vt` shared only where the same vertex has the same value, as the
/// UV layout counts values), and the value of every corner.
#[derive(Default)]
pub(super) struct FaceUvs {
    pub(super) coords: Vec<DVec2>,
    pub(super) corners: Vec<u32>,
    pub(super) ids: HashMap<[u64; 3], u32>,
}

impl FaceUvs {
    pub(super) fn bytes(&self) -> usize {
        std::mem::size_of_val(self.coords.as_slice())
            + std::mem::size_of_val(self.corners.as_slice())
            + 40 * self.ids.capacity()
    }
}

/// The reader of the data after the header, and what it keeps.
pub(super) struct Body<R> {
    pub(super) source: Source<R>,
    /// `None` for ASCII.
    pub(super) big_endian: Option<bool>,
    /// ASCII: the current line and the position of its next token.
    pub(super) text: String,
    pub(super) pos: usize,
    /// The line where binary data starts (for [`Error::MeshTooLarge`](crate::Error::MeshTooLarge)).
    pub(super) data_line: u64,
    pub(super) budget: Budget,
    pub(super) header_bytes: usize,
    pub(super) vertices: u64,
    pub(super) positions: Vec<DVec3>,
    pub(super) colors: Vec<[f64; 3]>,
    pub(super) vertex_uvs: Vec<DVec2>,
    pub(super) faces: Faces,
    pub(super) face_uvs: FaceUvs,
    /// The corners and texture coordinates of the face being read.
    pub(super) corners: Vec<u32>,
    pub(super) texcoord: Vec<f64>,
    /// Binary data: what is read ahead.
    pub(super) bytes: Bytes,
}

/// Where a value is: an element and its index, and the property.
#[derive(Clone, Copy)]
pub(super) struct At<'a> {
    pub(super) element: &'a Element,
    pub(super) index: u64,
}

impl<R: BufRead> Body<R> {
    pub(super) fn new(source: Source<R>, header: &Header, budget: Budget) -> Body<R> {
        let faces = match header.big_endian {
            None => Faces::Lines(Box::default()),
            Some(_) => Faces::Plain {
                offsets: vec![0],
                indices: Vec::new(),
            },
        };
        let data_line = header.end_line + 1;
        Body {
            source,
            big_endian: header.big_endian,
            text: String::new(),
            pos: 0,
            data_line,
            budget,
            header_bytes: header.bytes,
            vertices: header.vertices,
            positions: Vec::new(),
            colors: Vec::new(),
            vertex_uvs: Vec::new(),
            faces,
            face_uvs: FaceUvs::default(),
            corners: Vec::new(),
            texcoord: Vec::new(),
            bytes: Bytes::default(),
        }
    }

    pub(super) fn error(&self, at: At<'_>, property: Option<&Property>, kind: ParseError) -> Error {
        Error::PlyData {
            file: self.source.file.clone(),
            element: at.element.label.clone(),
            index: at.index,
            property: property.map(|p| p.label.clone()),
            kind: Box::new(kind),
        }
    }

    pub(super) fn truncated(&self, at: At<'_>, property: Option<&Property>) -> Error {
        let what = format!(
            "the header declares {} `{}` elements",
            at.element.count, at.element.label
        );
        self.error(at, property, ParseError::UnexpectedEnd { what })
    }

    pub(super) fn allocation_failed(
        &self,
        at: At<'_>,
        bytes: u128,
        e: std::collections::TryReserveError,
    ) -> Error {
        Error::AllocationFailed {
            what: format!(
                "the mesh read from {} ({} {})",
                self.source.file, at.element.label, at.index
            ),
            bytes,
            reason: e.to_string(),
        }
    }

    /// The bytes of everything kept so far (the mesh, the reader's lists, the header's).
    pub(super) fn used(&self) -> u128 {
        let kept = std::mem::size_of_val(self.positions.as_slice())
            + std::mem::size_of_val(self.colors.as_slice())
            + std::mem::size_of_val(self.vertex_uvs.as_slice())
            + self.faces.bytes()
            + self.face_uvs.bytes()
            + 4 * self.corners.capacity()
            + 8 * self.texcoord.capacity()
            + self.header_bytes;
        kept as u128
    }

    /// Refuses once `used() + adding` bytes outgrow the budget.
    pub(super) fn check(&self, adding: u128) -> Result<()> {
        if self.used() + adding > u128::from(self.budget.bytes) {
            return Err(self.too_large());
        }
        Ok(())
    }

    /// The refusal of what was read beyond the budget, where the reader got to.
    pub(super) fn too_large(&self) -> Error {
        let line = match self.big_endian {
            None => self.source.line,
            Some(_) => self.data_line,
        };
        Error::MeshTooLarge {
            file: self.source.file.clone(),
            line,
            limit: self.budget.bytes,
        }
    }

    /// Starts an element: ASCII data reads its line (blank lines are skipped).
    pub(super) fn begin(&mut self, at: At<'_>) -> Result<()> {
        if self.big_endian.is_some() {
            return Ok(());
        }
        loop {
            match self.source.next_line(&mut self.text) {
                Ok(true) if self.text.is_empty() => continue,
                Ok(true) => {
                    self.pos = 0;
                    return Ok(());
                }
                Ok(false) => return Err(self.truncated(at, None)),
                Err(LineError::Io(e)) => return Err(self.source.io(e)),
                Err(LineError::Bad(kind)) => return Err(self.error(at, None, kind)),
            }
        }
    }

    /// Ends an element: ASCII data must have no value left on its line.
    pub(super) fn end(&mut self, at: At<'_>) -> Result<()> {
        if self.big_endian.is_none() {
            if let Some((a, b)) = self.token() {
                let token = shorten(&self.text[a..b]);
                return Err(self.error(at, None, ParseError::UnexpectedToken { token }));
            }
        }
        Ok(())
    }

    /// The next whitespace-separated token of the ASCII line, as a range of `text`.
    pub(super) fn token(&mut self) -> Option<(usize, usize)> {
        crate::io::lines::next_word(self.text.as_bytes(), &mut self.pos)
    }

    /// The next value, of type `ty`, of `property`; with `finite`, a NaN or infinite value is
    /// an error.
    pub(super) fn scalar(
        &mut self,
        ty: Type,
        at: At<'_>,
        property: &Property,
        finite: bool,
    ) -> Result<f64> {
        let (value, token) = match self.big_endian {
            None => {
                let Some((a, b)) = self.token() else {
                    let kind = malformed("no value on the line");
                    return Err(self.error(at, Some(property), kind));
                };
                let token = &self.text[a..b];
                let Some(value) = ty.parse_text(token) else {
                    let kind = ParseError::InvalidNumber {
                        token: shorten(token),
                        expected: ty.name(),
                    };
                    return Err(self.error(at, Some(property), kind));
                };
                (value, Some((a, b)))
            }
            Some(big_endian) => {
                if !self.bytes.fill(&mut self.source.reader, ty.size()) {
                    return Err(match self.bytes.failure() {
                        Some(e) => self.source.io(e),
                        None => self.truncated(at, Some(property)),
                    });
                }
                (ty.decode(self.bytes.take(ty.size()), big_endian), None)
            }
        };
        if finite && !value.is_finite() {
            let token = match token {
                Some((a, b)) => shorten(&self.text[a..b]),
                None => value.to_string(),
            };
            let kind = ParseError::NonFiniteCoordinate { token };
            return Err(self.error(at, Some(property), kind));
        }
        Ok(value)
    }

    /// A list's count: an integer from 0 to [`MAX_LIST_ITEMS`].
    pub(super) fn list_count(&mut self, ty: Type, at: At<'_>, property: &Property) -> Result<u64> {
        let count = self.scalar(ty, at, property, false)?;
        if !(0.0..=MAX_LIST_ITEMS as f64).contains(&count) {
            let kind = ParseError::ListCount {
                count: count as i64,
                limit: MAX_LIST_ITEMS,
            };
            return Err(self.error(at, Some(property), kind));
        }
        Ok(count as u64)
    }

    /// Skips `n` values of type `ty` (ASCII values are checked to be numbers of the type).
    pub(super) fn skip(&mut self, ty: Type, n: u64, at: At<'_>, property: &Property) -> Result<()> {
        match self.big_endian {
            None => {
                for _ in 0..n {
                    self.scalar(ty, at, property, false)?;
                }
                Ok(())
            }
            Some(_) => {
                let bytes = n * ty.size() as u64;
                if self.skip_bytes(bytes)? < bytes {
                    return Err(self.truncated(at, Some(property)));
                }
                Ok(())
            }
        }
    }

    /// Skips up to `n` bytes of binary data; the bytes skipped.
    pub(super) fn skip_bytes(&mut self, n: u64) -> Result<u64> {
        let skipped = self.bytes.skip(&mut self.source.reader, n);
        skipped.map_err(|e| self.source.io(e))
    }

    /// Skips a property's value or list, checking it.
    pub(super) fn skip_property(&mut self, at: At<'_>, property: &Property) -> Result<()> {
        match property.shape {
            Shape::Scalar(ty) => self.skip(ty, 1, at, property),
            Shape::List { count, item } => {
                let n = self.list_count(count, at, property)?;
                self.skip(item, n, at, property)
            }
        }
    }

    /// Skips every value of an element no output carries.
    pub(super) fn skip_element(&mut self, element: &Element) -> Result<()> {
        if element.properties.is_empty() {
            return Ok(());
        }
        let scalars: Option<u64> = element
            .properties
            .iter()
            .map(|p| match p.shape {
                Shape::Scalar(ty) => Some(ty.size() as u64),
                Shape::List { .. } => None,
            })
            .sum();
        if let (Some(_), Some(stride)) = (self.big_endian, scalars) {
            // Fixed-size elements: skipped in one go.
            let total = u128::from(element.count) * u128::from(stride);
            let skipped = self.skip_bytes(u64::try_from(total).unwrap_or(u64::MAX))?;
            if u128::from(skipped) < total {
                let at = At {
                    element,
                    index: skipped / stride,
                };
                return Err(self.truncated(at, None));
            }
            return Ok(());
        }
        for index in 0..element.count {
            let at = At { element, index };
            self.begin(at)?;
            for property in &element.properties {
                self.skip_property(at, property)?;
            }
            self.end(at)?;
        }
        Ok(())
    }

    /// Reads the vertex element: positions, and colors and texture coordinates if the header
    /// has them.
    pub(super) fn vertices(&mut self, element: &Element) -> Result<()> {
        let colors = element
            .properties
            .iter()
            .any(|p| matches!(p.role, Role::Color(_)));
        let uvs = element
            .properties
            .iter()
            .any(|p| matches!(p.role, Role::VertexUv(_)));
        let room = |bytes: u64| {
            element
                .count
                .min(MAX_PREALLOCATED)
                .min(self.budget.bytes / 4 / bytes) as usize
        };
        let _ = self.positions.try_reserve_exact(room(24));
        if colors {
            let _ = self.colors.try_reserve_exact(room(24));
        }
        if uvs {
            let _ = self.vertex_uvs.try_reserve_exact(room(16));
        }
        // Binary records of scalars are read whole while all their bytes are there.
        let first = match self
            .big_endian
            .and_then(|b| Some((Layout::of(element)?, b)))
        {
            Some((layout, big_endian)) => {
                self.vertex_records(element, &layout, big_endian, (colors, uvs))?
            }
            None => 0,
        };
        for index in first..element.count {
            let at = At { element, index };
            self.begin(at)?;
            let (mut p, mut c, mut t) = ([0.0; 3], [0.0; 3], [0.0; 2]);
            for property in &element.properties {
                match (property.shape, property.role) {
                    (Shape::Scalar(ty), Role::Position(k)) => {
                        p[k] = self.scalar(ty, at, property, true)?;
                    }
                    (Shape::Scalar(ty), Role::Color(k)) => {
                        let value = self.scalar(ty, at, property, true)?;
                        c[k] = if ty == Type::U8 { value / 255.0 } else { value };
                    }
                    (Shape::Scalar(ty), Role::VertexUv(k)) => {
                        t[k] = self.scalar(ty, at, property, true)?;
                    }
                    _ => self.skip_property(at, property)?,
                }
            }
            self.end(at)?;
            self.push_vertex(at, p, (colors, c), (uvs, t))?;
        }
        Ok(())
    }

    /// Keeps a vertex read: its position, and its color and texture coordinate when the
    /// element has them.
    #[inline]
    pub(super) fn push_vertex(
        &mut self,
        at: At<'_>,
        p: [f64; 3],
        (colors, c): (bool, [f64; 3]),
        (uvs, t): (bool, [f64; 2]),
    ) -> Result<()> {
        let adding = 24 + if colors { 24 } else { 0 } + if uvs { 16 } else { 0 };
        self.check(adding)?;
        self.store_vertex(at, adding, p, (colors, c), (uvs, t))
    }

    /// Keeps a vertex whose `adding` bytes the budget has been checked for: its position,
    /// and its color and UV when the element has them.
    #[inline(always)]
    pub(super) fn store_vertex(
        &mut self,
        at: At<'_>,
        adding: u128,
        p: [f64; 3],
        (colors, c): (bool, [f64; 3]),
        (uvs, t): (bool, [f64; 2]),
    ) -> Result<()> {
        let refused = |body: &Self, e| body.allocation_failed(at, adding, e);
        self.positions
            .try_reserve(1)
            .map_err(|e| refused(self, e))?;
        self.positions.push(DVec3::from_array(p));
        if colors {
            self.colors.try_reserve(1).map_err(|e| refused(self, e))?;
            self.colors.push(c);
        }
        if uvs {
            self.vertex_uvs
                .try_reserve(1)
                .map_err(|e| refused(self, e))?;
            self.vertex_uvs.push(DVec2::from_array(t));
        }
        Ok(())
    }

    /// Reads the face element: corners, and texture coordinates if it has `texcoord`.
    pub(super) fn faces(&mut self, element: &Element) -> Result<()> {
        let texcoord = element.properties.iter().find(|p| p.role == Role::TexCoord);
        // Binary faces of only a list of corners are read whole while their bytes are there.
        let first = match (self.big_endian, element.properties.as_slice()) {
            (Some(big_endian), [p]) => match (p.shape, p.role) {
                (Shape::List { count, item }, Role::Indices) => {
                    self.corner_lists(element, (count, item), big_endian)?
                }
                _ => 0,
            },
            _ => 0,
        };
        for index in first..element.count {
            let at = At { element, index };
            self.begin(at)?;
            let line = self.source.line;
            self.corners.clear();
            self.texcoord.clear();
            for property in &element.properties {
                match (property.shape, property.role) {
                    (Shape::List { count, item }, Role::Indices) => {
                        let n = self.list_count(count, at, property)?;
                        if n < 3 {
                            let kind = ParseError::FaceTooSmall {
                                corners: n as usize,
                            };
                            return Err(self.error(at, None, kind));
                        }
                        // Binary corners are read whole (when all their bytes are there).
                        if let Some(big_endian) = self.big_endian {
                            if self.corner_list(item, n, big_endian, at)? {
                                continue;
                            }
                        }
                        for _ in 0..n {
                            let value = self.scalar(item, at, property, false)?;
                            let index = value as i64;
                            if index < 0 || index as u64 >= self.vertices {
                                let kind = ParseError::VertexIndexOutOfRange {
                                    index,
                                    vertices: self.vertices,
                                };
                                return Err(self.error(at, None, kind));
                            }
                            self.check(4)?;
                            self.corners
                                .try_reserve(1)
                                .map_err(|e| self.allocation_failed(at, 4, e))?;
                            self.corners.push(index as u32);
                        }
                    }
                    (Shape::List { count, item }, Role::TexCoord) => {
                        let n = self.list_count(count, at, property)?;
                        for _ in 0..n {
                            let value = self.scalar(item, at, property, true)?;
                            self.check(8)?;
                            self.texcoord
                                .try_reserve(1)
                                .map_err(|e| self.allocation_failed(at, 8, e))?;
                            self.texcoord.push(value);
                        }
                    }
                    _ => self.skip_property(at, property)?,
                }
            }
            self.end(at)?;
            let k = self.corners.len();
            if let Some(property) = texcoord {
                if self.texcoord.len() != 2 * k {
                    let what = format!(
                        "{} values for a face of {k} corners (expected {}: u v per corner)",
                        self.texcoord.len(),
                        2 * k
                    );
                    return Err(self.error(at, Some(property), malformed(what)));
                }
            }
            // The face's corners, offset and line; its corners' texture coordinates (at most
            // a new value, 16 bytes and a map entry, each).
            let uv_bytes = if texcoord.is_some() { 4 + 16 + 40 } else { 0 };
            let adding = (k * (4 + uv_bytes) + 16) as u128;
            self.check(adding)?;
            let corners = std::mem::take(&mut self.corners);
            let pushed = self.faces.push(&corners, line);
            self.corners = corners;
            pushed.map_err(|e| self.allocation_failed(at, adding, e))?;
            if texcoord.is_some() {
                self.push_face_uvs(at)?;
            }
        }
        Ok(())
    }

    /// Records the texture coordinates of the face just read (its corners in `corners`), a
    /// value per distinct (vertex, u, v).
    pub(super) fn push_face_uvs(&mut self, at: At<'_>) -> Result<()> {
        let uvs = &mut self.face_uvs;
        let failed = uvs
            .corners
            .try_reserve(self.texcoord.len() / 2)
            .and_then(|()| uvs.ids.try_reserve(self.texcoord.len() / 2))
            .and_then(|()| uvs.coords.try_reserve(self.texcoord.len() / 2));
        if let Err(e) = failed {
            return Err(self.allocation_failed(at, 52 * self.texcoord.len() as u128 / 2, e));
        }
        for (uv, &v) in self.texcoord.chunks_exact(2).zip(&self.corners) {
            let next = uvs.coords.len();
            if next >= u32::MAX as usize {
                let kind = malformed("more than 4294967294 distinct texture coordinates");
                return Err(self.error(at, None, kind));
            }
            let id = *uvs
                .ids
                .entry([u64::from(v), uv[0].to_bits(), uv[1].to_bits()])
                .or_insert(next as u32);
            if id as usize == next {
                uvs.coords.push(DVec2::new(uv[0], uv[1]));
            }
            uvs.corners.push(id);
        }
        Ok(())
    }

    /// The mesh read, with its colors, texture coordinates and what it does not carry.
    pub(super) fn finish(mut self, header: Header) -> Result<PolygonMesh> {
        if self.faces.n_faces() == 0 {
            return Err(Error::NoFaces {
                file: self.source.file.clone(),
            });
        }
        let uvs = match header.uvs {
            None => None,
            Some(UvSource::PerFace) => {
                let uvs = std::mem::take(&mut self.face_uvs);
                Some(Uvs::from_read(uvs.coords, uvs.corners))
            }
            Some(UvSource::PerVertex) => {
                // A value per vertex: each corner names its vertex's.
                let indices = self.faces.indices();
                self.check(4 * indices.len() as u128)?;
                let mut corners = Vec::new();
                if let Err(e) = corners.try_reserve_exact(indices.len()) {
                    return Err(Error::AllocationFailed {
                        what: format!("the texture coordinates read from {}", self.source.file),
                        bytes: 4 * indices.len() as u128,
                        reason: e.to_string(),
                    });
                }
                corners.extend_from_slice(indices);
                Some(Uvs::from_read(
                    std::mem::take(&mut self.vertex_uvs),
                    corners,
                ))
            }
        };
        let colors = header.colors.then(|| std::mem::take(&mut self.colors));
        let mut mesh = self.faces.into_mesh(self.positions);
        mesh.set_read_uvs(uvs, None);
        mesh.set_read_extras((colors, None), None, header.uncarried);
        Ok(mesh)
    }
}

// ---------------------------------------------------------------------------------------
// Writing.
