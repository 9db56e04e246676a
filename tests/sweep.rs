//! Parameter sweeps end to end: Example 3's bar, varied over k2, the second contact's point,
//! and a 2-D grid; shards; the plot; bad input.

use std::path::{Path, PathBuf};

use inertance::tools::sweep::{Shard, SweepError, SweepOptions, Vary, sweep};

/// Example 3: a bar on two supports, k1 = 0.3, k2 = 0.2.
const EXAMPLE_3: &str = r#"
name = "Example 3"
[body]
mass = 1
inertia = [12, 1.6, 12]
velocity = [3, 2, 0]
angular_velocity = [0, 0, 0.4]
[[contact]]
point = [0, -2, 0]
normal = [1, 0, 0]
k = 0.3
[[contact]]
point = [0, 4, 0]
normal = [1, 0, 0]
k = 0.2
"#;

/// A scratch directory holding the scene, removed when the test ends.
struct Scratch {
    dir: PathBuf,
}

impl Scratch {
    fn new(name: &str) -> Scratch {
        let dir =
            std::env::temp_dir().join(format!("inertance-sweep-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("scene.toml"), EXAMPLE_3).unwrap();
        Scratch { dir }
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }

    fn options(&self, vary: &[&str], out: &str) -> SweepOptions {
        SweepOptions {
            scene: self.path("scene.toml"),
            vary: vary.iter().map(|v| Vary::parse(v).unwrap()).collect(),
            out: self.path(out),
            ..SweepOptions::default()
        }
    }

    /// The files left in the directory, sorted.
    fn files(&self) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(&self.dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// The CSV as a header and rows of fields.
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::Reader::from_path(path).unwrap();
    let header = r.headers().unwrap().iter().map(String::from).collect();
    let rows = r
        .records()
        .map(|rec| rec.unwrap().iter().map(String::from).collect())
        .collect();
    (header, rows)
}

fn column(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"))
}

#[test]
fn exact_sweep_over_k2_newton_equals_poisson_only_at_k1() {
    let s = Scratch::new("k2");
    let opts = SweepOptions {
        exact: true,
        ..s.options(&["contact[1].k=0:1:11"], "out.csv")
    };
    let summary = sweep(&opts).unwrap();
    assert_eq!((summary.points, summary.singular), (11, 0));
    assert_eq!(
        s.files(),
        vec!["out.csv", "scene.toml"],
        "no .tmp left behind"
    );

    let (header, rows) = read_csv(&s.path("out.csv"));
    let want: Vec<&str> = [
        "point",
        "contact[1].k",
        "contact[1].k_exact",
        "newton_P1",
        "newton_P2",
        "newton_vCx",
        "newton_vCy",
        "newton_vCz",
        "newton_wx",
        "newton_wy",
        "newton_wz",
        "newton_Ep",
        "newton_dEc",
        "newton_P1_exact",
        "newton_P2_exact",
        "newton_Ep_exact",
        "newton_dEc_exact",
    ]
    .to_vec();
    assert_eq!(&header[..want.len()], &want[..]);
    assert_eq!(header.last().map(String::as_str), Some("status"));
    assert_eq!(header.len(), 3 + 2 * 14 + 1);

    assert_eq!(rows.len(), 11);
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row[0], i.to_string(), "rows in point order");
        let exact = [
            "0", "1/10", "1/5", "3/10", "2/5", "1/2", "3/5", "7/10", "4/5", "9/10", "1",
        ][i];
        assert_eq!(row[2], exact);
        assert_eq!(row[1].parse::<f64>().unwrap(), i as f64 / 10.0);
        assert_eq!(row.last().unwrap(), "ok");
        let same = ["P1_exact", "P2_exact", "dEc_exact"].iter().all(|c| {
            row[column(&header, &format!("newton_{c}"))]
                == row[column(&header, &format!("poisson_{c}"))]
        });
        // k1 = k2 = 0.3 only at i = 3: there, and only there, Newton = Poisson exactly.
        assert_eq!(same, i == 3, "row {i}: {row:?}");
    }
}

#[test]
fn shards_concatenate_to_the_unsharded_csv() {
    let s = Scratch::new("shards");
    for exact in [false, true] {
        let whole = SweepOptions {
            exact,
            ..s.options(&["contact[1].k=0:1:11"], "all.csv")
        };
        sweep(&whole).unwrap();
        let all = std::fs::read_to_string(s.path("all.csv")).unwrap();

        let mut joined = String::new();
        let mut points = 0;
        for i in 1..=3 {
            let name = format!("part-{i}.csv");
            let opts = SweepOptions {
                shard: Some(Shard::parse(&format!("{i}/3")).unwrap()),
                ..whole.clone()
            };
            let opts = SweepOptions {
                out: s.path(&name),
                ..opts
            };
            points += sweep(&opts).unwrap().points;
            let text = std::fs::read_to_string(s.path(&name)).unwrap();
            // Every shard has the header; `tail -n +2` drops it from all but the first.
            let body = if i == 1 {
                text.as_str()
            } else {
                text.split_once('\n').unwrap().1
            };
            joined.push_str(body);
        }
        assert_eq!(points, 11);
        assert_eq!(joined, all, "exact = {exact}");
    }
}

#[test]
fn two_dimensional_sweep_and_plot() {
    let s = Scratch::new("grid");
    let opts = SweepOptions {
        plot: Some(s.path("grid.svg")),
        threads: Some(2),
        progress: true,
        law: None,
        ..s.options(
            &["contact[1].k=0:1:5", "contact[0].k=0.1:0.9:3"],
            "grid.csv",
        )
    };
    let summary = sweep(&opts).unwrap();
    assert_eq!(summary.points, 15);
    let (header, rows) = read_csv(&s.path("grid.csv"));
    assert_eq!(&header[..3], &["point", "contact[1].k", "contact[0].k"]);
    assert_eq!(rows.len(), 15);
    // The first --vary is the outer index.
    for (p, row) in rows.iter().enumerate() {
        let (i, j) = (p / 3, p % 3);
        assert_eq!(row[1].parse::<f64>().unwrap(), i as f64 / 4.0);
        assert_eq!(row[2].parse::<f64>().unwrap(), [0.1, 0.5, 0.9][j]);
    }
    let svg = std::fs::read_to_string(s.path("grid.svg")).unwrap();
    assert!(svg.starts_with("<svg"), "{}", &svg[..svg.len().min(80)]);
    assert!(svg.contains("newton P1") && svg.contains("poisson dEc"));
    assert_eq!(s.files(), vec!["grid.csv", "grid.svg", "scene.toml"]);
}

#[test]
fn one_dimensional_plot_of_chosen_outputs() {
    let s = Scratch::new("plot");
    let opts = SweepOptions {
        plot: Some(s.path("k2.svg")),
        plot_outputs: vec!["P2".into(), "newton_dEc".into()],
        ..s.options(&["contact[1].k=0:1:21"], "k2.csv")
    };
    sweep(&opts).unwrap();
    let svg = std::fs::read_to_string(s.path("k2.svg")).unwrap();
    assert!(svg.starts_with("<svg"));
    assert!(svg.contains("newton P2") && svg.contains("poisson P2") && svg.contains("newton dEc"));
    assert!(!svg.contains("poisson dEc"));
    // Every point is admissible here (ω = 0.4: P2 > 0 for every k2), so nothing is shaded.
    assert!(
        !svg.contains("status "),
        "no regime band on an all-ok sweep"
    );
    assert!(
        svg.contains("contact[1].k"),
        "x axis named by the varied path"
    );
}

#[test]
fn a_singular_point_is_reported_not_an_error() {
    let s = Scratch::new("singular");
    for exact in [true, false] {
        // point[1] = -2, 0, 2, 4: at -2 the two contacts coincide, so Δ = 0.
        let opts = SweepOptions {
            exact,
            plot: Some(s.path("y.svg")),
            ..s.options(&["contact[1].point[1]=-2:4:4"], "y.csv")
        };
        let summary = sweep(&opts).unwrap();
        assert_eq!(
            (summary.points, summary.singular),
            (4, 1),
            "exact = {exact}"
        );
        let (header, rows) = read_csv(&s.path("y.csv"));
        let status = column(&header, "status");
        let p1 = column(&header, "newton_P1");
        assert_eq!(rows[0][status], "singular");
        let svg = std::fs::read_to_string(s.path("y.svg")).unwrap();
        assert!(
            svg.contains("status singular: -2"),
            "the singular point is marked"
        );
        assert_eq!(rows[0][p1], "");
        assert!(rows[0][2..status].iter().filter(|f| !f.is_empty()).count() <= 1);
        // The other points are solved; a simultaneous answer with a negative impulse says
        // `tensile` (never `ok`), one without says `ok` or names its other verdicts.
        let impulses: Vec<usize> = ["newton_P1", "newton_P2", "poisson_P1", "poisson_P2"]
            .iter()
            .map(|c| column(&header, c))
            .collect();
        for row in &rows[1..] {
            assert!(row[p1].parse::<f64>().is_ok());
            let tensile = impulses
                .iter()
                .any(|&c| row[c].parse::<f64>().unwrap() < 0.0);
            assert_eq!(row[status].contains("tensile"), tensile, "{row:?}");
            for reason in row[status].split('+') {
                assert!(
                    [
                        "ok",
                        "tensile",
                        "separating",
                        "still-approaching",
                        "energy-gain"
                    ]
                    .contains(&reason)
                );
            }
        }
    }
}

#[test]
fn bad_vary_names_the_path_and_value_and_leaves_no_file() {
    let s = Scratch::new("bad");
    let fails = |vary: &[&str]| -> SweepError {
        let e = sweep(&s.options(vary, "bad.csv")).unwrap_err();
        assert_eq!(e.exit_code(), 2, "{e}");
        e
    };
    // k up to 1.5: the stop value is not a coefficient of restitution.
    let e = fails(&["contact[1].k=0:1.5:4"]).to_string();
    assert!(
        e.contains("contact[1].k") && e.contains("1.5") && e.contains("[0, 1]"),
        "{e}"
    );
    // A path the scene does not have.
    let e = fails(&["contact[5].k=0:1:3"]).to_string();
    assert!(
        e.contains("contact[5].k") && e.contains("not a number or parameter of the scene"),
        "{e}"
    );
    let e = fails(&["body.density=1:2:3"]).to_string();
    assert!(e.contains("body.density") && e.contains("body.mass"), "{e}");
    // A vector where a number is needed.
    let e = fails(&["contact[1].point=0:1:3"]).to_string();
    assert!(e.contains("contact[1].point"), "{e}");
    // A mass through zero.
    let e = fails(&["body.mass=-1:1:3"]).to_string();
    assert!(
        e.contains("body.mass") && e.contains("-1") && e.contains("positive"),
        "{e}"
    );
    // The same input twice; three inputs; none.
    let e = fails(&["contact[1].k=0:1:3", "contact[1].k_newton=0:1:3"]).to_string();
    assert!(e.contains("already varied"), "{e}");
    let e = fails(&[
        "contact[1].k=0:1:3",
        "contact[0].k=0:1:3",
        "body.mass=1:2:3",
    ])
    .to_string();
    assert!(e.contains("one or two"), "{e}");
    let e = fails(&[]).to_string();
    assert!(e.contains("--vary"), "{e}");
    // A normal through zero is caught at the point where it happens.
    let e = fails(&["contact[1].normal[0]=-1:1:3"]);
    assert!(matches!(e, SweepError::Point { point: 1, .. }), "{e}");
    assert!(e.to_string().contains("contact[1].normal[0] = 0"), "{e}");

    assert_eq!(
        s.files(),
        vec!["scene.toml"],
        "nothing written on bad input"
    );
}

#[test]
fn bad_plot_output_and_unwritable_out() {
    let s = Scratch::new("io");
    let opts = SweepOptions {
        plot: Some(s.path("p.svg")),
        plot_outputs: vec!["P7".into()],
        ..s.options(&["contact[1].k=0:1:3"], "o.csv")
    };
    let e = sweep(&opts).unwrap_err();
    assert!(
        matches!(e, SweepError::Output { .. }) && e.exit_code() == 2,
        "{e}"
    );

    let opts = s.options(&["contact[1].k=0:1:3"], "no/such/dir/o.csv");
    let e = sweep(&opts).unwrap_err();
    assert!(
        matches!(e, SweepError::Io { .. }) && e.exit_code() == 1,
        "{e}"
    );
    assert!(e.to_string().contains("o.csv"), "{e}");
    assert_eq!(s.files(), vec!["scene.toml"]);
}

/// Example 3 (`examples/planar-bar.toml`) swept over ω_z from 0.4 to 1.2. By hand, with the
/// supports at y = −2 and y = 4 and n = x:
///
/// - v₁ₓ⁰ = v_x − ω_z·(−2) = 3 + 2ω, v₂ₓ⁰ = 3 − 4ω;
/// - g_ij = 1/m + y_i y_j / J_z: g₁₁ = 4/3, g₂₂ = 7/3, g₁₂ = 1/3, Δ = 3;
/// - Newton (eq. 20): P₂ = [g₁₁(1 + k₂)v₂ₓ⁰ − g₁₂(1 + k₁)v₁ₓ⁰]/Δ
///   = [1.6(3 − 4ω) − (1.3/3)(3 + 2ω)]/3, zero where 4.8(3 − 4ω) = 1.3(3 + 2ω), i.e.
///   ω* = 10.5/21.8 = **105/218** ≈ 0.4817, negative beyond (P₁ = [(7/3)1.3(3 + 2ω) −
///   (1/3)1.2(3 − 4ω)]/3 stays positive);
/// - Poisson: P₂ᶜ ∝ g₁₁v₂ₓ⁰ − g₁₂v₁ₓ⁰ ∝ 4(3 − 4ω) − (3 + 2ω), zero at ω = 1/2 > ω*: Newton
///   decides the switch;
/// - contact 2 separates before impact (v₂ₓ⁰ < 0) for ω > 3/4.
///
/// The grid 0.4:1.2:873 has ω_i = 2/5 + i/1090, and ω* − 2/5 = 89/1090: point 89 is exactly ω*
/// (P₂ = 0, still `ok`), point 90 the first `tensile`; ω_i > 3/4 ⇔ i > 381.5.
#[test]
fn sweeping_omega_crosses_into_tensile_at_the_threshold_of_eq_20_and_the_plot_marks_it() {
    let s = Scratch::new("omega");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/planar-bar.toml");
    for exact in [true, false] {
        let opts = SweepOptions {
            scene: scene.clone(),
            exact,
            plot: Some(s.path("w.svg")),
            ..s.options(&["body.angular_velocity[2]=0.4:1.2:873"], "w.csv")
        };
        sweep(&opts).unwrap();
        let (header, rows) = read_csv(&s.path("w.csv"));
        let status = column(&header, "status");
        assert_eq!(rows.len(), 873);
        for (i, row) in rows.iter().enumerate() {
            let st = &row[status];
            if i <= 89 {
                assert_eq!(st, "ok", "point {i}, exact = {exact}");
            } else {
                assert!(
                    st.starts_with("tensile"),
                    "point {i}: {st}, exact = {exact}"
                );
                assert_eq!(st.contains("separating"), i >= 382, "point {i}: {st}");
            }
        }
        if exact {
            let w = column(&header, "body.angular_velocity[2]_exact");
            assert_eq!(rows[89][w], "105/218");
            assert_eq!(rows[89][column(&header, "newton_P2_exact")], "0");
        }
        let svg = std::fs::read_to_string(s.path("w.svg")).unwrap();
        // The band from the first tensile point (ω₉₀ = 2/5 + 90/1090 = 263/545 ≈ 0.4826) to the
        // last before contact 2 separates (ω₃₈₁ = 817/1090 ≈ 0.7495), in the legend and shaded.
        assert!(
            svg.contains("status tensile: 0.4826…0.7495"),
            "exact = {exact}"
        );
        assert!(
            svg.contains("status tensile+separating: 0.7505…"),
            "exact = {exact}"
        );
        assert!(
            svg.contains(r##"opacity="0.15" fill="#D62728""##),
            "the tensile band"
        );
        // The rest of the plot is as before.
        assert!(svg.contains("newton P2") && svg.contains("poisson dEc"));
    }
}
