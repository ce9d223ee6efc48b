//! Initial states from typed counts through `Scheme::state_from_input`.

use num_bigint::BigInt;
use schemes::{builtin, parse_init, CountsInput, Error};

fn state(scheme: &str, counts: &str) -> Result<Vec<i64>, Error> {
    let s = builtin(scheme)?;
    let x = s.state_from_input(&counts.parse::<CountsInput>()?)?;
    Ok(x.iter().map(|v| i64::try_from(v).unwrap()).collect())
}

#[test]
fn identities_fill_the_state() {
    // Closed triangles: IE = E, BE = 0; loop's state is (V, E).
    assert_eq!(state("loop", "V=12,E=30,F=20").unwrap(), [12, 30]);
    assert_eq!(state("loop", "F=20,V=12").unwrap(), [12, 30]);
    assert_eq!(
        state("loop-boundary", "V=12,E=30,F=20").unwrap(),
        [12, 30, 0]
    );
    assert_eq!(state("loop-boundary", "V=6,E=9,F=4").unwrap(), [6, 3, 6]);
    assert_eq!(
        state("loop-general", "V=12,E=30,F=20").unwrap(),
        [12, 30, 20]
    );
    // E = IE + BE + NME.
    assert_eq!(
        state("catmull-clark-quad", "V=4,IE=0,BE=4,NME=0,F=1").unwrap(),
        [4, 4, 1]
    );
    // Any polygon mesh with manifold edges: H = 2IE + BE.
    assert_eq!(
        state("catmull-clark", "V=5,IE=0,BE=5,F=1").unwrap(),
        [5, 0, 5, 1, 5]
    );
    assert_eq!(
        state("catmull-clark", "V=8,E=12,F=6,BE=0").unwrap(),
        [8, 12, 0, 6, 24]
    );
    assert_eq!(
        state("sqrt3-boundary", "V=3,E=3,F=1").unwrap(),
        [3, 0, 3, 1]
    );
    assert_eq!(state("doo-sabin", "V=8,E=12,F=6").unwrap(), [8, 12, 6]);
}

#[test]
fn what_is_missing_is_listed() {
    assert_eq!(
        state("catmull-clark", "V=8,E=12,F=6").unwrap_err().to_string(),
        "catmull-clark needs IE, BE, H in its initial state, which the given counts do not \
         determine; give IE, BE, H as well (e.g. IE=...,BE=...,H=...), or the whole initial state in order"
    );
    assert!(matches!(
        state("catmull-clark-general", "V=8,E=12,F=6"),
        Err(Error::MissingComponents { missing, .. }) if missing == ["H"]
    ));
}

#[test]
fn contradictions_and_refusals() {
    assert_eq!(
        state("loop-boundary", "V=12,E=30,IE=29,BE=2").unwrap_err().to_string(),
        "the counts contradict each other: E=30 given but IE + BE = 31 (identities for a \
         triangle mesh with edges of one or two faces: E = IE + BE + NME, NME = 0, H = 2IE + BE, H = 3F)"
    );
    assert!(state("loop", "V=12,E=30,F=21")
        .unwrap_err()
        .to_string()
        .contains("2E = 60 but 3F = 63"));
    assert_eq!(
        state("loop", "V=12,E=30,BE=3").unwrap_err().to_string(),
        "loop needs a closed mesh, but BE=3; use loop-boundary"
    );
    assert_eq!(
        state("loop-boundary", "V=5,E=7,F=3,NME=1")
            .unwrap_err()
            .to_string(),
        "loop-boundary needs every edge to have one or two faces, but NME=1; use loop-general"
    );
    assert_eq!(
        state("loop", "V=12,X=3").unwrap_err().to_string(),
        "unknown count `X` for loop; use V, E, IE, BE, NME, F, H"
    );
    assert!(matches!(
        state("loop-boundary", "V=6,E=9,F=7"),
        Err(Error::ImpossibleDerived { name, .. }) if name == "BE"
    ));
}

#[test]
fn plain_initial_vectors() {
    assert_eq!(parse_init("12, 30").unwrap(), [12, 30].map(BigInt::from));
    assert_eq!(
        parse_init(" 1, -2 ,3").unwrap(),
        [1, -2, 3].map(BigInt::from)
    );
    assert_eq!(
        parse_init("1,x").unwrap_err().to_string(),
        "initial state `1,x`: `x` is not an integer"
    );
    // One grammar with `subcount --init`: an empty value, brackets or spaces between
    // values are refused.
    for (text, item) in [("1,,2", ""), ("", ""), ("[1,2]", "[1"), ("1 2", "1 2")] {
        assert!(
            matches!(parse_init(text), Err(Error::InitSyntax { item: i, .. }) if i == item),
            "{text}"
        );
    }
    let l = builtin("loop").unwrap();
    assert_eq!(
        l.check_state(&parse_init("1,2,3").unwrap())
            .unwrap_err()
            .to_string(),
        "loop has 2 state components (V, E), but 3 values were given"
    );
}
