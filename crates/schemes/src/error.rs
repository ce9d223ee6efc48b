//! The error type of the `schemes` crate.

/// A `Result` whose error defaults to this crate's [`Error`].
pub type Result<T = (), E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong when choosing, loading or applying a scheme.
///
/// Every variant describes bad input (a name, a file, counts that do not fit a scheme); none is
/// a bug in this crate. Messages are lowercase, without a trailing period, and name what is
/// wrong and where.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// No built-in scheme has this name.
    #[error("unknown scheme `{name}`; built-in schemes: {known}")]
    UnknownScheme {
        /// The name asked for.
        name: String,
        /// The built-in names and aliases, comma separated.
        known: String,
    },
    /// `tri-split-N` with an `N` that is not an integer >= 2 or is too large.
    #[error("`{name}`: {reason}")]
    InvalidSplitFactor {
        /// The name asked for, e.g. `tri-split-1`.
        name: String,
        /// Why the factor is refused.
        reason: String,
    },
    /// The scheme does not apply to this mesh (wrong face kind, boundary, non-manifold edges).
    #[error("{scheme} needs {needs}, but {found}{}", hint_text(.hint))]
    NotApplicable {
        /// The scheme that refused.
        scheme: String,
        /// What the scheme needs, e.g. `a triangle mesh`.
        needs: String,
        /// What the mesh has instead, e.g. `this mesh has 6 faces of degree 4`.
        found: String,
        /// The scheme to use instead, when there is one.
        hint: Option<String>,
    },
    /// A state component cannot be computed from the counts at hand.
    #[error("{scheme} needs {} in its initial state, which the given counts do not determine{}", .missing.join(", "), hint_text(.hint))]
    MissingComponents {
        /// The scheme (or plan stage) whose state is incomplete.
        scheme: String,
        /// The state components still unknown.
        missing: Vec<String>,
        /// What to give in addition.
        hint: Option<String>,
    },
    /// Given counts contradict each other (through a documented identity).
    #[error("the counts contradict each other: {detail}")]
    Contradiction {
        /// The values involved and the identity they break, e.g.
        /// `E=30 given but IE + BE + NME = 31 (identity E = IE + BE + NME)`.
        detail: String,
    },
    /// A value derived through an identity is negative or not an integer.
    #[error("{name} = {formula} = {value} is not a count (the counts do not describe a {class})")]
    ImpossibleDerived {
        /// The derived quantity.
        name: String,
        /// The identity used, e.g. `2E - 3F`.
        formula: String,
        /// The derived value, possibly a fraction.
        value: String,
        /// The mesh class assumed, e.g. `triangle mesh with edges of one or two faces`.
        class: String,
    },
    /// The counts of a [`MeshCounts`](crate::MeshCounts) are inconsistent.
    #[error("inconsistent mesh counts: {detail}")]
    InconsistentCounts {
        /// Which identity fails, with values.
        detail: String,
    },
    /// A face list given to [`MeshCounts::from_polygons`](crate::MeshCounts::from_polygons) is
    /// unusable.
    #[error("face {face}: {reason}")]
    BadFace {
        /// Zero-based index of the face.
        face: usize,
        /// What is wrong with it.
        reason: String,
    },
    /// `--counts` text could not be parsed.
    #[error("counts `{text}`: {reason}")]
    CountsSyntax {
        /// The whole text.
        text: String,
        /// What is wrong and where.
        reason: String,
    },
    /// A count is negative.
    #[error("count {key}={value} is negative; counts are non-negative integers")]
    NegativeCount {
        /// The key.
        key: String,
        /// The value given.
        value: String,
    },
    /// A key is given twice.
    #[error("count {key} is given twice")]
    DuplicateKey {
        /// The key.
        key: String,
    },
    /// A key of the counts is neither a mesh statistic nor a state component of the scheme.
    #[error("unknown count `{key}` for {scheme}; use {known}")]
    UnknownKey {
        /// The key given.
        key: String,
        /// The scheme the counts were meant for.
        scheme: String,
        /// The accepted keys, comma separated.
        known: String,
    },
    /// An `--init` vector could not be parsed.
    #[error("initial state `{text}`: `{item}` is not an integer")]
    InitSyntax {
        /// The whole text.
        text: String,
        /// The first value that is not an integer (trimmed; empty for an empty value).
        item: String,
    },
    /// An initial state has the wrong number of values.
    #[error("{scheme} has {expected} state components ({names}), but {got} values were given")]
    InitialLength {
        /// The scheme.
        scheme: String,
        /// Number of values given.
        got: usize,
        /// Number of state components.
        expected: usize,
        /// The component names, comma separated.
        names: String,
    },
    /// V, E or F is neither a state component nor derivable for this scheme.
    #[error("{scheme} does not say how to count {what} (add it to `derive`)")]
    NoMeshCounts {
        /// The scheme.
        scheme: String,
        /// `V`, `E` or `F`.
        what: String,
    },
    /// A derived V, E or F is not an integer for this state.
    #[error("{what} = {formula} = {value} is not an integer for this state of {scheme}")]
    NotIntegral {
        /// The scheme.
        scheme: String,
        /// `V`, `E` or `F`.
        what: String,
        /// The derivation, e.g. `2E/3`.
        formula: String,
        /// The rational value.
        value: String,
    },
    /// A custom scheme file is invalid.
    #[error("line {line}, column {column}: {message}")]
    SchemeFile {
        /// One-based line of the problem in the TOML text.
        line: usize,
        /// One-based column (in characters).
        column: usize,
        /// What is wrong.
        message: String,
    },
    /// A scheme specification is inconsistent (built with
    /// [`Scheme::try_from_spec`](crate::Scheme::try_from_spec) or
    /// [`StepRule::try_new`](crate::StepRule::try_new)).
    #[error("scheme {scheme}: {reason}")]
    InvalidSpec {
        /// The scheme's name (empty when not known yet).
        scheme: String,
        /// What is wrong.
        reason: String,
    },
    /// A matrix product (one period of a cycle) overflows `i64`.
    #[error("the product of the matrices of {scheme} over one period overflows i64")]
    PeriodOverflow {
        /// The scheme.
        scheme: String,
    },
    /// A composition `A:k,B` could not be parsed.
    #[error("scheme plan `{text}`: {reason}")]
    PlanSyntax {
        /// The whole text.
        text: String,
        /// What is wrong.
        reason: String,
    },
    /// A level beyond the last stage of a plan whose last stage has a level count.
    #[error("level {level} is beyond the plan, which ends at level {last}")]
    LevelBeyondPlan {
        /// The level asked for.
        level: u64,
        /// The last level of the plan.
        last: u64,
    },
    /// Even level 0 exceeds the budget of a `fit`.
    #[error("level 0 does not fit: {detail}")]
    NothingFits {
        /// Which limit is exceeded and by how much.
        detail: String,
    },
    /// A search needs counts that never decrease, and these do.
    #[error("{what} decreases from level {level} to level {next} ({from} -> {to}); fit and density searches need counts that never decrease from level 1")]
    NotMonotone {
        /// The quantity, e.g. `V`.
        what: String,
        /// The earlier level.
        level: u64,
        /// The later level.
        next: u64,
        /// The value at `level`.
        from: String,
        /// The value at `next`.
        to: String,
    },
    /// A `fit` was asked without any limit.
    #[error(
        "no limit given: set a maximum number of vertices, edges or faces, or a memory budget"
    )]
    NoLimit,
    /// A budget limits UV values (`max_uv`, `bytes_per_uv`) but the search has no UV layout
    /// to count them from ([`fit`](crate::fit) rather than [`fit_uv`](crate::fit_uv)).
    #[error("a UV limit needs a mesh with a UV layout (texture coordinates at every face corner)")]
    NoUvLayout,
    /// A byte size such as `2GiB` could not be parsed.
    #[error("byte size `{text}`: {reason}")]
    ByteSize {
        /// The text given.
        text: String,
        /// What is wrong.
        reason: String,
    },
    /// Bad arguments to [`density`](crate::density) or a target-area search.
    #[error("density: {reason}")]
    Density {
        /// What is wrong.
        reason: String,
    },
    /// A floating-point figure of [`density`](crate::density) or a target-area search is
    /// infinite, not a number or zero where the exact value is positive: it cannot be
    /// printed as a number.
    #[error("density: {what} {reason}")]
    OutOfFloatRange {
        /// The figure, e.g. `the mean co-volume area 4 pi r^2 / V`.
        what: String,
        /// Why it is out of range, with the inputs that made it so.
        reason: String,
    },
    /// A search would need states too large to compute (a quantity grows slowly while
    /// another component of the state explodes), or reached the last level a `u64` can name
    /// while the counts still grow (polynomial growth against a huge budget).
    #[error("the search reached level {level}, where the state has {bits} bits, without crossing the limit; refusing to go further")]
    SearchTooLarge {
        /// The level reached.
        level: u64,
        /// Total bits of the state there.
        bits: u64,
    },
    /// A search would reach a level whose counts are estimated too large to compute (an
    /// early stage of a composition that runs for a huge number of levels).
    #[error("the search would reach level {level}, where the counts would have about {digits} decimal digits; refusing to go further")]
    SearchEstimateTooLarge {
        /// The level.
        level: u64,
        /// The estimated decimal digits of the largest count there, e.g. `1.111e19`.
        digits: String,
    },
    /// The target of a search is never reached (the counts stop growing).
    #[error("{what} never reaches {target}: it is {value} from level {level} on and stays there")]
    NeverReached {
        /// The quantity, e.g. `V`.
        what: String,
        /// The target.
        target: String,
        /// The value it stays at.
        value: String,
        /// The level from which it is constant.
        level: u64,
    },
    /// A predicted count does not fit the integer type asked for ([`LevelCounts`]'s
    /// accessors, e.g. `vertices_usize`).
    ///
    /// [`LevelCounts`]: crate::LevelCounts
    #[error("level {level} has {count} {what}: more than {target} can hold")]
    CountDoesNotFit {
        /// `vertices`, `edges` or `faces`.
        what: &'static str,
        /// The level.
        level: u64,
        /// The exact count.
        count: num_bigint::BigInt,
        /// The type, e.g. `usize`.
        target: &'static str,
    },
    /// A UV layout given to [`UvCounts::from_layout`](crate::uv::UvCounts::from_layout) is
    /// inconsistent (offsets, corner counts, a value out of range or at two vertices).
    #[error("UV layout: {reason}")]
    BadUvLayout {
        /// What is wrong and where.
        reason: String,
    },
    /// An error of the underlying recurrence (names, dimensions).
    #[error(transparent)]
    Recurrence(#[from] recurrence::Error),
}

fn hint_text(hint: &Option<String>) -> String {
    match hint {
        Some(h) => format!("; {h}"),
        None => String::new(),
    }
}
