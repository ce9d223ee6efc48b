//! `fit`, byte sizes and the density helpers.

use num_bigint::BigInt;
use schemes::{
    fit, level_for_area, parse_byte_size, Budget, CountsInput, Error, Fit, MemoryBudget, Plan,
    Scheme,
};

fn ico(plan: &Plan) -> Vec<BigInt> {
    plan.state_from_input(&"V=12,E=30,F=20".parse::<CountsInput>().unwrap())
        .unwrap()
}

fn vertices(n: u64) -> Budget {
    Budget {
        max_vertices: Some(BigInt::from(n)),
        ..Budget::default()
    }
}

#[test]
fn fit_matches_a_linear_scan() {
    let plan = Plan::parse("loop").unwrap();
    let x0 = ico(&plan);
    // V: 12, 42, 162, 642, 2562, ...
    for (limit, level) in [(12, 0), (41, 0), (42, 1), (641, 2), (642, 3), (2561, 3)] {
        let Fit::Level(c) = fit(&plan, &x0, &vertices(limit)).unwrap() else {
            panic!("bounded")
        };
        assert_eq!(c.level, level, "limit {limit}");
    }
    // Against a scan for several schemes and budgets (faces and bytes too).
    for name in [
        "catmull-clark",
        "sqrt3-boundary",
        "doo-sabin",
        "loop:3,loop-general",
        "catmull-clark:1,catmull-clark-quad",
    ] {
        let plan = Plan::parse(name).unwrap();
        let x0 = plan
            .first()
            .initial_state(&pick_mesh(plan.first()))
            .unwrap();
        for bytes in [200u64, 5_000, 123_456, 10_000_000, 4_000_000_000] {
            let budget = Budget {
                max_faces: Some(BigInt::from(bytes / 3)),
                memory: Some(MemoryBudget {
                    bytes: BigInt::from(bytes),
                    bytes_per_vertex: 12,
                    bytes_per_edge: 0,
                    bytes_per_face: 12,
                    bytes_per_uv: 0,
                }),
                ..Budget::default()
            };
            let scan = (0..64u64)
                .take_while(|&s| {
                    let c = plan.level_counts(&x0, s).unwrap();
                    12 * &c.vertices + 12 * &c.faces <= BigInt::from(bytes)
                        && c.faces <= BigInt::from(bytes / 3)
                })
                .last();
            match (fit(&plan, &x0, &budget), scan) {
                (Ok(Fit::Level(c)), Some(s)) => assert_eq!(c.level, s, "{name} {bytes}"),
                (Ok(Fit::NoneFits { .. }), None) => {}
                (got, want) => panic!("{name} {bytes}: {got:?} vs {want:?}"),
            }
        }
    }
}

fn pick_mesh(s: &Scheme) -> schemes::MeshCounts {
    let faces: Vec<Vec<u32>> = match s.canonical_name() {
        "doo-sabin" | "loop" => vec![vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![2, 0, 3]],
        _ => vec![vec![0, 3, 1], vec![1, 3, 4], vec![1, 4, 2], vec![2, 4, 5]],
    };
    schemes::MeshCounts::from_polygons(&faces).unwrap()
}

#[test]
fn fit_edge_cases() {
    let plan = Plan::parse("loop").unwrap();
    let x0 = ico(&plan);
    assert!(matches!(
        fit(&plan, &x0, &vertices(11)).unwrap(),
        Fit::NoneFits { detail, .. } if detail == "V = 12 > 11"
    ));
    assert!(matches!(
        fit(&plan, &x0, &Budget::default()),
        Err(Error::NoLimit)
    ));
    // An empty mesh never grows: every level fits.
    let zero = vec![BigInt::from(0); 2];
    assert!(matches!(
        fit(&plan, &zero, &vertices(0)).unwrap(),
        Fit::Unbounded { counts } if counts.vertices == BigInt::from(0)
    ));
    // A custom scheme whose counts stop growing after one step.
    let settles = Scheme::from_toml(
        "name = \"settles\"\nstate = [\"V\", \"E\", \"F\"]\nmatrix = [[1, 1, 0], [0, 0, 0], [0, 0, 1]]\n",
    )
    .unwrap();
    let plan = Plan::from(settles);
    let x0 = [10, 5, 3].map(BigInt::from);
    assert!(matches!(
        fit(&plan, &x0, &vertices(100)).unwrap(),
        Fit::Unbounded { counts } if counts.vertices == BigInt::from(15)
    ));
    // Polynomial growth: V(s) = V0 + s E0 with E constant.
    let linear = Scheme::from_toml(
        "name = \"linear\"\nstate = [\"V\", \"E\", \"F\"]\nmatrix = [[1, 1, 0], [0, 1, 0], [0, 0, 1]]\n",
    )
    .unwrap();
    let plan = Plan::from(linear);
    let Fit::Level(c) = fit(
        &plan,
        &[0, 1, 0].map(BigInt::from),
        &vertices(1_000_000_000),
    )
    .unwrap() else {
        panic!("grows")
    };
    assert_eq!(c.level, 1_000_000_000);
    // V grows linearly while a hidden component explodes: the search stops before the
    // state becomes too large to compute.
    let explodes = Scheme::from_toml(
        "name = \"explodes\"\nstate = [\"V\", \"E\", \"F\", \"x\"]\nmatrix = [[1, 1, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 4]]\n",
    )
    .unwrap();
    let err = fit(
        &Plan::from(explodes),
        &[0, 1, 0, 1].map(BigInt::from),
        &vertices(u64::MAX),
    )
    .unwrap_err();
    assert!(matches!(err, Error::SearchTooLarge { .. }), "{err}");
    // A scheme whose vertex count decreases is refused.
    let shrinks = Scheme::from_toml(
        "name = \"shrinks\"\nstate = [\"V\", \"E\", \"F\"]\nmatrix = [[1, -1, 0], [0, 2, 0], [0, 0, 1]]\n",
    )
    .unwrap();
    let err = fit(
        &Plan::from(shrinks),
        &[100, 1, 0].map(BigInt::from),
        &vertices(1000),
    )
    .unwrap_err();
    assert!(matches!(err, Error::NotMonotone { .. }), "{err}");
    // A bounded plan: the last level when everything fits.
    let plan = Plan::parse("loop:1,loop-general:2").unwrap();
    let Fit::Level(c) = fit(&plan, &ico(&plan), &vertices(1 << 40)).unwrap() else {
        panic!("bounded plan")
    };
    assert_eq!(c.level, 3);
}

#[test]
fn huge_budgets_are_exact() {
    // 2^200 vertices under loop: V(s) = 12 + 10 (4^s - 1) <= 2^200 up to s = 98.
    let plan = Plan::parse("loop").unwrap();
    let budget = Budget {
        max_vertices: Some(BigInt::from(1) << 200),
        ..Budget::default()
    };
    let Fit::Level(c) = fit(&plan, &ico(&plan), &budget).unwrap() else {
        panic!("bounded")
    };
    assert_eq!(c.level, 98);
    assert_eq!(c.vertices, BigInt::from(10) * (BigInt::from(1) << 196) + 2);
}

#[test]
fn byte_sizes() {
    assert_eq!(parse_byte_size("2GiB").unwrap(), 2_147_483_648);
    assert_eq!(parse_byte_size("2GB").unwrap(), 2_000_000_000);
    assert_eq!(parse_byte_size("512 MiB").unwrap(), 512 << 20);
    assert_eq!(parse_byte_size("1kb").unwrap(), 1000);
    assert_eq!(parse_byte_size("0").unwrap(), 0);
    assert_eq!(parse_byte_size("0.5KiB").unwrap(), 512);
    for (text, reason) in [
        ("", "expected a number, e.g. 2GiB"),
        ("GiB", "expected a number, e.g. 2GiB"),
        (
            "2 XB",
            "unknown unit (use B, kB, MB, GB, TB, PB, EB, KiB, MiB, GiB, TiB, PiB or EiB)",
        ),
        ("1.2.3GB", "not a number"),
        ("0.1B", "not a whole number of bytes"),
        ("-2GiB", "expected a number, e.g. 2GiB"),
        ("999999999999999999999999999999999999999999EiB", "too large"),
    ] {
        assert_eq!(
            parse_byte_size(text).unwrap_err().to_string(),
            format!("byte size `{text}`: {reason}")
        );
    }
}

#[test]
fn density_and_target_areas() {
    let plan = Plan::parse("icosphere").unwrap();
    let x0 = ico(&plan);
    // Earth radius 6371 km, 100 km^2 target: 4 pi r^2 / 100 = 5.1e6 vertices: level 10 has
    // 10485762, level 9 has 2621442.
    let c = level_for_area(&plan, &x0, 6371.0, 100.0).unwrap();
    assert_eq!(c.level, 10);
    assert_eq!(c.vertices, BigInt::from(10_485_762));
    let d = schemes::density(&c.vertices, 6371.0, 4.0).unwrap();
    assert!(d.mean_area <= 100.0 && d.mean_area > 40.0);
    // A target already met at level 0.
    assert_eq!(level_for_area(&plan, &x0, 1.0, 100.0).unwrap().level, 0);
    assert!(matches!(
        schemes::density(&BigInt::from(0), 1.0, 1.0),
        Err(Error::Density { .. })
    ));
    assert!(matches!(
        level_for_area(&plan, &x0, -1.0, 1.0),
        Err(Error::Density { .. })
    ));
    let zero = vec![BigInt::from(0); 2];
    assert!(matches!(
        level_for_area(&plan, &zero, 1.0, 1.0),
        Err(Error::NeverReached { .. })
    ));
}

/// "Nothing fits" is an answer, with level 0's counts and each exceeded limit; as counts it
/// is the error `subcount fit` reports.
#[test]
fn none_fits_is_an_answer() {
    let plan = Plan::parse("loop").unwrap();
    let x0 = ico(&plan);
    let budget = Budget {
        max_vertices: Some(BigInt::from(11)),
        max_faces: Some(BigInt::from(20)),
        ..Budget::default()
    };
    let answer = fit(&plan, &x0, &budget).unwrap();
    let Fit::NoneFits { counts, detail } = &answer else {
        panic!("{answer:?}")
    };
    assert_eq!((counts.level, detail.as_str()), (0, "V = 12 > 11"));
    assert_eq!(answer.highest_level(64), None);
    assert_eq!(
        answer.counts().unwrap_err().to_string(),
        "level 0 does not fit: V = 12 > 11"
    );
    // Within the budget from level 0 on, every level fits for a constant scheme: the cap.
    let constant = Scheme::from_toml(
        "name = \"c\"\nstate = [\"V\", \"E\", \"F\"]\nmatrix = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n",
    )
    .unwrap();
    let every = fit(
        &Plan::from(constant),
        &[10, 5, 3].map(BigInt::from),
        &vertices(100),
    )
    .unwrap();
    assert!(matches!(every, Fit::Unbounded { .. }), "{every:?}");
    assert_eq!(every.highest_level(30), Some(30));
    assert_eq!(every.counts().unwrap().level, 0);
}

/// With a UV layout, `fit_uv` finds what a linear scan over the UV values (and bytes with
/// `bytes_per_uv`) finds, for single schemes and compositions; `fit` refuses a UV limit.
#[test]
fn fit_uv_matches_a_linear_scan_of_the_uv_values() {
    use schemes::uv::UvCounts;
    use schemes::{fit_uv, Counter, Error};
    // spot_control_mesh's layout (with 3 split values, to count them) and its state.
    let spot = UvCounts {
        values: 267,
        edges: 438,
        boundary_edges: 144,
        used_vt: 267,
        faces: 180,
        corners: 732,
        split_values: 3,
        ..UvCounts::default()
    };
    let x0 = [188, 366, 0, 180, 732].map(BigInt::from);
    for text in ["catmull-clark", "catmull-clark:2,catmull-clark"] {
        let plan = Plan::parse(text).unwrap();
        let uv = Counter::from(plan.clone()).uv_counter(&spot).unwrap();
        for limit in [300u64, 885, 886, 3225, 50_000, 10_000_000] {
            let budget = Budget {
                max_uv: Some(BigInt::from(limit)),
                ..Budget::default()
            };
            let scan = (0..64u64)
                .take_while(|&s| uv.values_at(s).unwrap() <= BigInt::from(limit))
                .last();
            let got = fit_uv(&plan, &x0, &uv, &budget).unwrap().highest_level(64);
            assert_eq!(got, scan, "{text} max_uv {limit}");
            assert_eq!(schemes::fit(&plan, &x0, &budget), Err(Error::NoUvLayout));
        }
        for bytes in [10_000u64, 123_456, 4_000_000_000] {
            let memory = MemoryBudget {
                bytes: BigInt::from(bytes),
                bytes_per_vertex: 12,
                bytes_per_face: 16,
                bytes_per_uv: 8,
                ..MemoryBudget::default()
            };
            let budget = Budget {
                memory: Some(memory),
                ..Budget::default()
            };
            let scan = (0..64u64)
                .take_while(|&s| {
                    let c = plan.level_counts(&x0, s).unwrap();
                    let uv = uv.values_at(s).unwrap();
                    12 * &c.vertices + 16 * &c.faces + 8 * uv <= BigInt::from(bytes)
                })
                .last();
            let got = fit_uv(&plan, &x0, &uv, &budget).unwrap().highest_level(64);
            assert_eq!(got, scan, "{text} {bytes} bytes");
        }
    }
}
