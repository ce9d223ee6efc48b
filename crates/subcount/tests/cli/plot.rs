//! `plot`: a well-formed SVG with the expected labels, a PNG of the expected size, atomic
//! output, and the errors.

use crate::util::{data, fails, file_names, ok, subcount};

const LOOP_ICO: [&str; 5] = ["plot", "--scheme", "loop", "--counts", "V=12,E=30,F=20"];

fn plot_args<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut v: Vec<&str> = LOOP_ICO.to_vec();
    v.extend_from_slice(extra);
    v
}

/// Every text element's text (plotters writes it on its own line), in document order.
fn all_texts(doc: &roxmltree::Document<'_>) -> Vec<String> {
    text_nodes(doc).map(|n| text_of(&n)).collect()
}

fn text_nodes<'a>(
    doc: &'a roxmltree::Document<'_>,
) -> impl Iterator<Item = roxmltree::Node<'a, 'a>> + 'a {
    doc.descendants().filter(|n| n.has_tag_name("text"))
}

fn text_of(node: &roxmltree::Node<'_, '_>) -> String {
    node.text().unwrap_or("").trim().to_string()
}

fn number(node: &roxmltree::Node<'_, '_>, attribute: &str) -> f64 {
    node.attribute(attribute)
        .unwrap_or_else(|| panic!("no {attribute} on {node:?}"))
        .parse()
        .unwrap()
}

/// The powers of ten on the y axis, as "10^k": the labels written "10" with a superscript
/// exponent ("10¹²").
fn powers(doc: &roxmltree::Document<'_>) -> Vec<String> {
    let exponent = |c: char| "⁰¹²³⁴⁵⁶⁷⁸⁹".chars().position(|d| d == c);
    all_texts(doc)
        .iter()
        .filter_map(|t| {
            let digits = t.strip_prefix("10")?.chars().map(exponent);
            let k: Option<String> = digits.map(|d| char::from_digit(d? as u32, 10)).collect();
            k.filter(|k| !k.is_empty()).map(|k| format!("10^{k}"))
        })
        .collect()
}

/// The points of every series line: the 2-pixel polylines inside the plot frame (the grid
/// lines are 1 pixel wide, the legend's samples lie right of the frame).
fn polylines(doc: &roxmltree::Document<'_>) -> Vec<Vec<(f64, f64)>> {
    let frame = doc
        .descendants()
        .find(|n| n.has_tag_name("rect") && n.attribute("stroke") == Some("#444444"))
        .expect("a plot frame");
    let right = number(&frame, "x") + number(&frame, "width");
    doc.descendants()
        .filter(|n| n.has_tag_name("polyline") && n.attribute("stroke-width") == Some("2"))
        .map(|n| {
            n.attribute("points")
                .expect("a polyline has points")
                .split_whitespace()
                .map(|p| {
                    let (x, y) = p.split_once(',').expect("x,y");
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect::<Vec<(f64, f64)>>()
        })
        // A marker outline is a closed polyline; a series line runs left to right.
        .filter(|line| line.iter().all(|&(x, _)| x < right) && line.first() != line.last())
        .collect()
}

/// The filled, colored circle markers (each sits on a white halo circle).
fn colored_circles(doc: &roxmltree::Document<'_>) -> usize {
    doc.descendants()
        .filter(|n| n.has_tag_name("circle"))
        .filter(|n| !matches!(n.attribute("fill"), Some("#FFFFFF" | "none") | None))
        .count()
}

#[test]
fn svg_is_well_formed_with_labels_legend_and_title() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("counts.svg");
    let path = path.to_str().unwrap();
    let out = ok(&plot_args(&["--levels", "0..=12", "-o", path]));
    assert_eq!(out, format!("wrote {path} (3 series, levels 0..=12)\n"));
    assert_eq!(
        file_names(dir.path()),
        ["counts.svg"],
        "no temporary file is left"
    );

    let svg = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&svg).expect("well-formed XML");
    let root = doc.root_element();
    assert!(root.has_tag_name(("http://www.w3.org/2000/svg", "svg")));
    assert_eq!(root.attribute("width"), Some("960"));
    assert_eq!(root.attribute("height"), Some("600"));

    let texts = all_texts(&doc);
    assert_eq!(texts[0], "loop on V=12,E=30,F=20", "the title comes first");
    for label in [
        "loop on V=12,E=30,F=20",
        "level",
        "count (log scale)",
        "V (vertices)",
        "E (edges)",
        "F (faces)",
        "exact counts at levels 0..=12, log scale",
    ] {
        assert!(
            texts.iter().any(|t| t == label),
            "no text {label:?} in {texts:?}"
        );
    }
    // Level ticks 0..=12 and decade ticks 10^1 .. 10^9 (written as 10 with a raised exponent).
    for level in 0..=12 {
        assert!(texts.contains(&level.to_string()), "no tick {level}");
    }
    let powers = powers(&doc);
    for k in 2..=9 {
        assert!(
            powers.contains(&format!("10^{k}")),
            "no tick 10^{k} in {powers:?}"
        );
    }
    // The y label is turned a quarter.
    let ylabel = text_nodes(&doc)
        .find(|n| text_of(n) == "count (log scale)")
        .unwrap();
    assert!(ylabel
        .attribute("transform")
        .unwrap()
        .starts_with("rotate(270"));

    // One line per series, one point per level, rising (y down) at log10(4) per level for F
    // (positions are whole pixels: each step within a pixel of the mean step).
    let lines = polylines(&doc);
    assert_eq!(lines.len(), 3);
    for line in &lines {
        assert_eq!(line.len(), 13);
        assert!(
            line.windows(2).all(|w| w[1].0 > w[0].0 && w[1].1 < w[0].1),
            "{line:?}"
        );
    }
    let f = &lines[2];
    let step = (f[0].1 - f[12].1) / 12.0;
    assert!(step > 20.0, "{f:?}");
    for w in f.windows(2) {
        assert!(
            (w[0].1 - w[1].1 - step).abs() <= 1.0,
            "F is 20 * 4^s: equal steps, {f:?}"
        );
    }
    // V: log10 162 - log10 42 over log10 4 of F's step, from the exact counts.
    let v = &lines[0];
    let expected = (162f64.log10() - 42f64.log10()) / 4f64.log10() * step;
    assert!((v[1].1 - v[2].1 - expected).abs() <= 1.0, "{v:?}");
}

#[test]
fn png_has_the_signature_size_and_colors() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("counts.png");
    let path = path.to_str().unwrap();
    let out = ok(&plot_args(&["--levels", "0..=12", "-o", path]));
    assert_eq!(out, format!("wrote {path} (3 series, levels 0..=12)\n"));
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(&bytes[12..16], b"IHDR");
    assert_eq!(u32::from_be_bytes(bytes[16..20].try_into().unwrap()), 960);
    assert_eq!(u32::from_be_bytes(bytes[20..24].try_into().unwrap()), 600);

    let image = image::load_from_memory(&bytes).expect("a readable PNG");
    assert_eq!(image.color(), image::ColorType::Rgb8);
    let rgb: Vec<[u8; 3]> = image.to_rgb8().pixels().map(|p| p.0).collect();
    assert_eq!(rgb.len(), 960 * 600);
    assert_eq!(rgb[0], [255, 255, 255], "white background");
    // The three series colors and dark text are drawn.
    for color in [[0x1f, 0x77, 0xb4], [0xff, 0x7f, 0x0e], [0x2c, 0xa0, 0x2c]] {
        let n = rgb.iter().filter(|p| **p == color).count();
        assert!(n > 200, "{n} pixels of {color:?}");
    }
    let dark = rgb.iter().filter(|p| p.iter().all(|&c| c < 0x60)).count();
    assert!(dark > 1000, "{dark} dark (text and axis) pixels");
    // The title is drawn near the top center: dark pixels in rows 15..40 around x = 480.
    let title_ink = (15..40)
        .flat_map(|y| (380..580).map(move |x| (x, y)))
        .filter(|&(x, y)| rgb[y * 960 + x].iter().all(|&c| c < 0x80))
        .count();
    assert!(title_ink > 100, "{title_ink} title pixels");
}

#[test]
fn huge_counts_and_wide_level_ranges() {
    // Counts of 243 digits at level 400: positions from the exact counts, never infinite.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("wide.svg");
    let path = path.to_str().unwrap();
    ok(&plot_args(&["--levels", "0..=400", "-o", path]));
    let svg = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&svg).expect("well-formed XML");
    // At this scale V, E and F lie within a pixel of each other: V is one solid line through
    // the 401 levels, and E and F are dashed over it, each dash a short polyline of its own.
    let lines = polylines(&doc);
    assert_eq!(lines[0].len(), 401);
    assert!(lines[1..].iter().all(|l| l.len() < 401));
    assert!(lines.len() > 1 + 2 * 20, "{} polylines", lines.len());
    for line in &lines {
        for &(x, y) in line {
            assert!(
                (0.0..=960.0).contains(&x) && (0.0..=600.0).contains(&y),
                "({x}, {y})"
            );
        }
    }
    let texts = all_texts(&doc);
    let powers = powers(&doc);
    // F(400) = 20 * 4^400 ~ 10^242.1: the axis reaches 10^250 in steps of 50 decades.
    for power in ["10^50", "10^100", "10^250"] {
        assert!(
            powers.iter().any(|p| p == power),
            "no {power} in {powers:?}"
        );
    }
    for label in ["400", "200"] {
        assert!(texts.iter().any(|t| t == label), "no {label} in {texts:?}");
    }
    // No markers at this density, but still the legend's.
    assert_eq!(colored_circles(&doc), 1, "only the legend's V marker");
}

#[test]
fn plot_meshes_schemes_and_zero_columns() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("cc.svg");
    let path = path.to_str().unwrap();
    let out = ok(&[
        "plot",
        "--scheme",
        "catmull-clark",
        "--base",
        "cube",
        "--levels",
        "6",
        "-o",
        path,
    ]);
    assert_eq!(out, format!("wrote {path} (5 series, levels 0..=6)\n"));
    let svg = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let texts = all_texts(&doc);
    assert!(
        texts.contains(&"catmull-clark on cube".to_string()),
        "{texts:?}"
    );
    // BE is 0 on a closed mesh: not drawable on a log scale, and the legend says so.
    assert!(
        texts.contains(&"BE: no positive count".to_string()),
        "{texts:?}"
    );
    // E equals IE on a closed mesh: the legend says which line hides which.
    assert!(texts.contains(&"E (edges) = IE".to_string()), "{texts:?}");
    // Both lines of a pair that coincide stay visible: F lies within 2 of V from level 1 on,
    // E on IE. The earlier line is solid with filled markers, the later one dashed with marker
    // outlines (each dash and each outline a polyline of its own).
    let strokes = |color: &str| {
        doc.descendants()
            .filter(|n| n.has_tag_name("polyline") && n.attribute("stroke") == Some(color))
            .count()
    };
    let legend = |label: &str| texts.iter().position(|t| t == label).unwrap();
    assert!(legend("V (vertices)") < legend("F (faces)"));
    assert!(legend("IE (interior edges)") < legend("E (edges) = IE"));
    let [v, ie, f, e] = ["#1F77B4", "#FF7F0E", "#2CA02C", "#9467BD"].map(strokes);
    assert_eq!((v, ie), (2, 2), "one line each, and the legend's sample");
    assert!(f > 7 + 1 && e > 7 + 1, "dashes and outlines: F {f}, E {e}");
    assert_eq!(
        colored_circles(&doc),
        7 + 1,
        "V's filled markers, and the legend's"
    );

    let path = dir.path().join("tetra.png");
    let path = path.to_str().unwrap();
    let mesh = data("tetra.obj");
    ok(&[
        "plot", "--scheme", "loop", "--mesh", &mesh, "--levels", "3..=5", "-o", path,
    ]);
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");

    let path = dir.path().join("fib.svg");
    let path = path.to_str().unwrap();
    ok(&[
        "plot",
        "--matrix",
        "[[1,1],[1,0]]",
        "--init",
        "1,0",
        "--levels",
        "1..=20",
        "-o",
        path,
    ]);
    let svg = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let texts = all_texts(&doc);
    assert!(
        texts.contains(&"matrix [[1,1],[1,0]] on initial state 1,0".to_string()),
        "{texts:?}"
    );
    // x1 is 0 at level 0 only, which the range leaves out: both lines have 20 points.
    assert!(polylines(&doc).iter().all(|l| l.len() == 20));
}

/// A level whose count is not positive (off a log scale) breaks the line into runs; the
/// other lines and the markers stay.
#[test]
fn lines_break_where_a_count_is_not_positive() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("gap.svg");
    let path = path.to_str().unwrap();
    // x0 = (s - 2)^2 is 0 at level 2, x1 = 2s - 3 is negative at levels 0 and 1, x2 = 2.
    let matrix = "[[1,1,0],[0,1,1],[0,0,1]]";
    let args = [
        "plot", "--matrix", matrix, "--init", "4,-3,2", "--levels", "0..=5",
    ];
    let out = ok(&[&args[..], &["-o", path]].concat());
    assert_eq!(out, format!("wrote {path} (3 series, levels 0..=5)\n"));
    let svg = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let lengths: Vec<usize> = polylines(&doc).iter().map(Vec::len).collect();
    assert_eq!(lengths, [2, 3, 4, 6], "x0 in two runs, then x1 and x2");
    // Higher counts are drawn higher (smaller y): x0 rises from level 3 to 5.
    let x0 = &polylines(&doc)[1];
    assert!(x0.windows(2).all(|w| w[1].1 < w[0].1), "{x0:?}");
    assert_eq!(
        colored_circles(&doc),
        5 + 1,
        "x0's markers, and the legend's"
    );
    let texts = all_texts(&doc);
    let title = format!("matrix {matrix} on initial state 4,-3,2");
    assert_eq!(texts[0], title);
}

#[test]
fn plot_errors() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["counts.jpg", "counts"] {
        let path = dir.path().join(name);
        let err = fails(
            &plot_args(&["-o", path.to_str().unwrap()]),
            2,
            ".svg or .png",
        );
        assert!(err.contains(name), "{err}");
    }
    let path = dir.path().join("x.svg");
    let path = path.to_str().unwrap();
    fails(
        &plot_args(&["--levels", "0..=5000", "-o", path]),
        2,
        "a plot shows at most 1000",
    );
    fails(
        &plot_args(&["--levels", "7..=3", "-o", path]),
        2,
        "inverted",
    );
    fails(&plot_args(&[]), 2, "--output");
    // The resource guard: counts of ~6 * 10^8 digits.
    fails(
        &plot_args(&["--levels", "1000000000..=1000000002", "-o", path]),
        4,
        "decimal digits",
    );
    fails(
        &["plot", "--scheme", "loop", "--counts", "V=12", "-o", path],
        2,
        "needs E",
    );
    assert!(
        file_names(dir.path()).is_empty(),
        "nothing written on errors"
    );
    // A folder that does not exist: exit 3 naming the file, and no partial output anywhere.
    fails(
        &plot_args(&["-o", "/no/such/folder/counts.svg"]),
        3,
        "cannot write /no/such/folder/counts.svg",
    );
    // Overwriting an existing file replaces it whole.
    let path = dir.path().join("again.svg");
    std::fs::write(&path, "old").unwrap();
    let run = subcount(&plot_args(&["--levels", "2", "-o", path.to_str().unwrap()]));
    assert_eq!(run.code, 0, "{}", run.stderr);
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(svg.starts_with("<svg") && svg.ends_with("</svg>\n"));
    assert_eq!(file_names(dir.path()), ["again.svg"]);
}

/// Text from the command line (here a mesh file name) is escaped in the SVG.
#[test]
fn svg_escapes_names() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("a&b<c>'\".obj");
    std::fs::copy(data("tetra.obj"), &mesh).unwrap();
    let path = dir.path().join("escaped.svg");
    ok(&[
        "plot",
        "--scheme",
        "loop",
        "--mesh",
        mesh.to_str().unwrap(),
        "--levels",
        "3",
        "-o",
        path.to_str().unwrap(),
    ]);
    let svg = std::fs::read_to_string(&path).unwrap();
    let doc = roxmltree::Document::parse(&svg).expect("well-formed XML");
    let texts = all_texts(&doc);
    assert_eq!(texts[0], "loop on a&b<c>'\".obj");
}
