//! Faces on one vertex set: the search validation and the defect counts share.

/// Faces on the vertex set of an earlier face: how many, and the first such pair.
pub(crate) struct DuplicateFaces {
    /// Faces whose set of distinct vertices equals that of an earlier face.
    pub(crate) count: u64,
    /// The smallest pair `(first, second)`, `first < second`, of faces on one vertex set.
    pub(crate) first_pair: Option<(u32, u32)>,
}

/// A well-mixed 64-bit value of a vertex index (splitmix64), summed over a face to get a
/// hash of its vertex set that does not depend on the order.
fn mix(v: u32) -> u64 {
    let mut z = u64::from(v).wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A hash of a sorted, deduplicated vertex set.
fn set_hash(set: &[u32]) -> u64 {
    set.iter().fold(set.len() as u64, |h, &v| {
        h.wrapping_mul(0x100_0000_01b3).wrapping_add(mix(v))
    })
}

/// Finds the faces on equal vertex sets in linear time: two such faces have the same
/// smallest vertex, so the faces are bucketed by it (a counting sort) and, within a bucket,
/// sorted by a hash of their set; only faces of equal hash have their sets compared (so a
/// file of identical faces costs one sort, not a comparison of every pair). Indices far
/// beyond the face count (a raw list's stray index) sort all faces by hash instead.
pub(crate) fn duplicate_faces<'a>(
    n_faces: usize,
    face: &impl Fn(usize) -> &'a [u32],
) -> DuplicateFaces {
    let least = |f: usize| face(f).iter().copied().min().unwrap_or(0);
    let mut found = DuplicateFaces {
        count: 0,
        first_pair: None,
    };
    let top = (0..n_faces).map(least).max().unwrap_or(0) as usize;
    let mut keyed: Vec<(u64, u32)> = Vec::new();
    if top > 4 * n_faces + 1024 {
        keyed.extend((0..n_faces as u32).map(|f| (face_hash(face(f as usize)), f)));
        same_sets(&mut keyed, face, &mut found);
        return found;
    }
    let mut start = vec![0u32; top + 2];
    for f in 0..n_faces {
        start[least(f) as usize + 1] += 1;
    }
    for v in 0..=top {
        start[v + 1] += start[v];
    }
    let mut order = vec![0u32; n_faces];
    let mut fill = start.clone();
    for f in 0..n_faces {
        let slot = &mut fill[least(f) as usize];
        order[*slot as usize] = f as u32;
        *slot += 1;
    }
    drop(fill);
    for bucket in start.windows(2) {
        let bucket = &order[bucket[0] as usize..bucket[1] as usize];
        if bucket.len() > 1 {
            keyed.clear();
            keyed.extend(bucket.iter().map(|&f| (face_hash(face(f as usize)), f)));
            same_sets(&mut keyed, face, &mut found);
        }
    }
    found
}

/// The hash of a face's set of distinct vertices (whatever their order and repeats); faces of
/// up to 16 corners are sorted on the stack.
pub(super) fn face_hash(face: &[u32]) -> u64 {
    let mut small = [0u32; 16];
    let mut large = Vec::new();
    let set: &mut [u32] = if face.len() <= small.len() {
        small[..face.len()].copy_from_slice(face);
        &mut small[..face.len()]
    } else {
        large.extend_from_slice(face);
        &mut large
    };
    set.sort_unstable();
    let mut distinct = 0;
    for i in 0..set.len() {
        if i == 0 || set[i] != set[i - 1] {
            set[distinct] = set[i];
            distinct += 1;
        }
    }
    set_hash(&set[..distinct])
}

/// Counts the faces of `keyed` (hash, face) on the set of another, comparing sets only
/// within a hash, and keeps the smallest pair.
fn same_sets<'a>(
    keyed: &mut [(u64, u32)],
    face: &impl Fn(usize) -> &'a [u32],
    found: &mut DuplicateFaces,
) {
    let distinct_set = |f: u32| {
        let mut s = face(f as usize).to_vec();
        s.sort_unstable();
        s.dedup();
        s
    };
    keyed.sort_unstable();
    // Sorted by hash: a run of one hash holds every face with that set (and any collision).
    for run in keyed
        .chunk_by(|x, y| x.0 == y.0)
        .filter(|run| run.len() > 1)
    {
        // Sorted by set, then by face: each run of one set starts with its two smallest faces.
        let mut group: Vec<(Vec<u32>, u32)> =
            run.iter().map(|&(_, f)| (distinct_set(f), f)).collect();
        group.sort_unstable();
        for same in group
            .chunk_by(|x, y| x.0 == y.0)
            .filter(|same| same.len() > 1)
        {
            found.count += same.len() as u64 - 1;
            let candidate = (same[0].1, same[1].1);
            found.first_pair = Some(found.first_pair.map_or(candidate, |p| p.min(candidate)));
        }
    }
}
