//! The structure-aware scene generator: a valid scene built from the public schema (free body,
//! `[constraints]` in the paper's form or as joints, `[surface]`), then mutated.
//!
//! A small seeded generator of our own rather than proptest strategies: a case is a pure
//! function of one `u64` seed, so a failure is reproduced by that number alone (printed and
//! written beside the scene), any slice of a long run can be re-run in isolation, and the cost
//! of a case is what the commands spend, not strategy trees or shrinking (a shrunk TOML text is
//! rarely smaller than the hand-minimised corpus file we keep anyway).

/// SplitMix64: tiny, fast, and the same on every platform.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in 0..n (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    /// True with probability p.
    pub fn chance(&mut self, p: f64) -> bool {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64 <= p
    }

    pub fn pick<'a, T>(&mut self, xs: &'a [T]) -> &'a T {
        &xs[self.below(xs.len())]
    }

    /// An integer in lo..=hi.
    pub fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + self.below((hi - lo + 1) as usize) as i64
    }
}

/// One TOML table: its header (`None` the root, `"body"`, `"[contact]"` an array of tables) and
/// its entries as raw text `key = value`.
#[derive(Clone, Debug)]
pub struct Table {
    pub header: Option<String>,
    pub entries: Vec<(String, String)>,
}

/// A scene under construction, and what the harness needs to run it.
#[derive(Clone, Debug)]
pub struct Case {
    pub tables: Vec<Table>,
    /// Symbols to declare for `derive` (the scene may name some of them).
    pub symbols: Vec<String>,
    /// A `--vary` spec for `sweep`.
    pub vary: String,
    /// Number of contacts as generated (before mutation).
    pub contacts: usize,
    /// What was done to the valid scene, for the finding's header.
    pub mutations: Vec<String>,
    /// Raw-text damage applied after rendering (truncation, a stray byte).
    pub raw: Option<(usize, Option<char>)>,
}

impl Case {
    pub fn render(&self) -> String {
        let mut s = String::new();
        for t in &self.tables {
            match &t.header {
                None => {}
                Some(h) if h.starts_with('[') => s += &format!("\n[{h}]\n"),
                Some(h) => s += &format!("\n[{h}]\n"),
            }
            for (k, v) in &t.entries {
                s += &format!("{k} = {v}\n");
            }
        }
        if let Some((at, c)) = self.raw {
            let mut cut = at.min(s.len());
            while !s.is_char_boundary(cut) {
                cut -= 1;
            }
            match c {
                None => s.truncate(cut),
                Some(c) => s.insert(cut, c),
            }
        }
        s
    }

    /// (table index, entry index) of every entry.
    fn slots(&self) -> Vec<(usize, usize)> {
        let mut v = Vec::new();
        for (i, t) in self.tables.iter().enumerate() {
            for j in 0..t.entries.len() {
                v.push((i, j));
            }
        }
        v
    }

    fn contact_tables(&self) -> Vec<usize> {
        (0..self.tables.len())
            .filter(|&i| self.tables[i].header.as_deref() == Some("[contact]"))
            .collect()
    }

    fn get(&self, t: usize, key: &str) -> Option<usize> {
        self.tables[t].entries.iter().position(|(k, _)| k == key)
    }

    fn set(&mut self, t: usize, key: &str, value: String) {
        match self.get(t, key) {
            Some(j) => self.tables[t].entries[j].1 = value,
            None => self.tables[t].entries.push((key.to_string(), value)),
        }
    }
}

/// Extreme values, as TOML literals and as strings.
pub const EXTREMES: &[&str] = &[
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "5e-324",
    "-5e-324",
    "2.2250738585072014e-308",
    "1e-400",
    "1e400",
    "0",
    "-0.0",
    "0.0",
    "nan",
    "+nan",
    "-nan",
    "inf",
    "-inf",
    "+inf",
    "99999999999999999999999",
    "9223372036854775807",
    "-9223372036854775808",
    "0x7fffffff",
    "1_000_000",
    "1e-300",
    "1e300",
    "3.0e-320",
    "\"1e-400\"",
    "\"1e400\"",
    "\"2^-99999\"",
    "\"2^99999\"",
    "\"2^-99999999\"",
    "\"1e308\"",
    "\"5e-324\"",
    "\"NaN\"",
    "\"nan\"",
    "\"inf\"",
    "\"-inf\"",
    "\"Infinity\"",
    "\"1/0\"",
    "\"0/0\"",
    "\"2^1023\"",
    "\"2^1024\"",
    "\"2^-1074\"",
    "\"2^-1075\"",
    "\"10^400\"",
    "\"10^-400\"",
    "\"1e5000\"",
    "\"1e5001\"",
    "\"1e-5001\"",
    "\"sqrt(-1)\"",
    "\"\"",
    "\" \"",
    "\"pi\"",
    "\"9^9^9\"",
    "\"2^2^2^2^2\"",
    "\"(2^1000)^1000\"",
    "\"1/3\"",
    "\"sqrt(2)\"",
    "\"cos(30 deg)\"",
    "\"tan(90 deg)\"",
    "\"-0\"",
    "\"1e-30\"",
    "\"1e30\"",
    "\"1/(1-1)\"",
    "\"0^0\"",
    "\"0^-1\"",
    "\"x\"",
    "\"m\"",
    "\"2*\"",
    "\"((((1))))\"",
];

/// Values of the wrong type or shape.
const WRONG: &[&str] = &[
    "true",
    "\"abc\"",
    "[]",
    "[1]",
    "[1, 2]",
    "[1, 2, 3, 4]",
    "[[1, 2, 3]]",
    "{ a = 1 }",
    "[\"1\", true, 3]",
    "1979-05-27",
    "[1, [2], 3]",
    "{}",
    "[\"nan\", 0, 0]",
];

fn num(r: &mut Rng) -> String {
    match r.below(6) {
        0 => format!("{}", r.int(-5, 5)),
        1 => format!("{}.{}", r.int(-3, 3), r.int(0, 9)),
        2 => format!("\"{}/{}\"", r.int(-9, 9), r.int(1, 9)),
        3 => format!("{}", r.int(-2, 2)),
        4 => format!("{}e{}", r.int(1, 9), r.int(-3, 3)),
        _ => format!("{}", r.int(-20, 20)),
    }
}

fn pos(r: &mut Rng) -> String {
    match r.below(5) {
        0 => format!("{}", r.int(1, 20)),
        1 => format!("{}.{}", r.int(0, 3), r.int(1, 9)),
        2 => format!("\"{}/{}\"", r.int(1, 9), r.int(1, 9)),
        3 => format!("{}e{}", r.int(1, 9), r.int(-12, 12)),
        _ => "1".into(),
    }
}

fn vec3(r: &mut Rng) -> String {
    format!("[{}, {}, {}]", num(r), num(r), num(r))
}

fn ints(v: [i64; 3]) -> String {
    format!("[{}, {}, {}]", v[0], v[1], v[2])
}

fn cross(a: [i64; 3], b: [i64; 3]) -> [i64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn kval(r: &mut Rng) -> String {
    r.pick(&["0", "1", "0.3", "0.5", "\"1/3\"", "0.25", "0.9"])
        .to_string()
}

/// A contact table with `point` and `normal` (and sometimes a perpendicular tangent, split k).
fn contact(r: &mut Rng, point: String, normal: Option<[i64; 3]>) -> Table {
    let mut e = vec![("point".to_string(), point)];
    if let Some(n) = normal {
        e.push(("normal".into(), ints(n)));
        if r.chance(0.3) {
            // Perpendicular: n × e_k for some axis not parallel to n.
            let axes = [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
            let t = axes.iter().map(|&a| cross(n, a)).find(|t| *t != [0, 0, 0]);
            if let Some(t) = t {
                e.push(("tangent".into(), ints(t)));
            }
        }
    }
    if r.chance(0.2) {
        e.push(("k_newton".into(), kval(r)));
        e.push(("k_poisson".into(), kval(r)));
    } else {
        e.push(("k".into(), kval(r)));
    }
    Table {
        header: Some("[contact]".into()),
        entries: e,
    }
}

fn small_dir(r: &mut Rng) -> [i64; 3] {
    loop {
        let d = [r.int(-2, 2), r.int(-2, 2), r.int(-2, 2)];
        if d != [0, 0, 0] {
            return d;
        }
    }
}

/// The valid scene: a free body, a constrained one, or one with a surface.
fn base(r: &mut Rng) -> Case {
    let mut root = Table {
        header: None,
        entries: vec![],
    };
    if r.chance(0.7) {
        root.entries
            .push(("name".into(), format!("\"fuzz {}\"", r.below(1000))));
    }
    let mut body = Table {
        header: Some("body".into()),
        entries: vec![
            ("mass".into(), pos(r)),
            (
                "inertia".into(),
                format!("[{}, {}, {}]", pos(r), pos(r), pos(r)),
            ),
        ],
    };
    let mut tables = vec![];
    let kind = r.below(10);
    let n;
    if kind < 6 {
        // Free body, 1..=4 contacts mostly, sometimes many.
        n = match r.below(20) {
            0 => r.int(20, 300) as usize,
            1..=2 => r.int(5, 12) as usize,
            _ => r.int(1, 4) as usize,
        };
        body.entries.push(("velocity".into(), vec3(r)));
        body.entries.push(("angular_velocity".into(), vec3(r)));
        tables.push(root);
        tables.push(body);
        for _ in 0..n {
            let p = if n > 12 {
                format!("[{}, {}, {}]", r.int(-9, 9), r.int(-9, 9), r.int(-9, 9))
            } else {
                vec3(r)
            };
            let nrm = small_dir(r);
            tables.push(contact(r, p, Some(nrm)));
        }
    } else if kind < 8 {
        // Constrained: joints with an allowed twist, or the paper's form (Example 6's bar).
        n = r.int(1, 3) as usize;
        let t = r.int(-3, 3);
        let mut cons = Table {
            header: Some("constraints".into()),
            entries: vec![],
        };
        let mut joints = vec![];
        let (w, v);
        if r.chance(0.5) {
            cons.entries.push((
                "free".into(),
                "[[0, 0, 1, -1, 0, 0], [0, 0, 0, 1, 0, 0]]".into(),
            ));
            if r.chance(0.3) {
                cons.entries.push((
                    "blocked".into(),
                    "[[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 0, 0, 0, 1]]"
                        .into(),
                ));
            }
            let b = r.int(-3, 3);
            w = [0, 0, t];
            v = [b - t, 0, 0];
        } else {
            let a = small_dir(r);
            let p = [r.int(-2, 2), r.int(-2, 2), r.int(-2, 2)];
            let kindj = *r.pick(&[
                "revolute",
                "prismatic",
                "cylindrical",
                "spherical",
                "planar",
            ]);
            let mut j = Table {
                header: Some("[constraints.joint]".into()),
                entries: vec![("kind".into(), format!("\"{kindj}\""))],
            };
            match kindj {
                "revolute" | "cylindrical" => {
                    j.entries.push(("point".into(), ints(p)));
                    j.entries.push(("axis".into(), ints(a)));
                    w = [t * a[0], t * a[1], t * a[2]];
                    v = cross(p, w);
                }
                "prismatic" => {
                    j.entries.push(("axis".into(), ints(a)));
                    w = [0, 0, 0];
                    v = [t * a[0], t * a[1], t * a[2]];
                }
                "spherical" => {
                    j.entries.push(("point".into(), ints(p)));
                    w = [t, r.int(-2, 2), 0];
                    v = cross(p, w);
                }
                _ => {
                    j.entries.push(("normal".into(), ints(a)));
                    w = [t * a[0], t * a[1], t * a[2]];
                    v = [0, 0, 0];
                }
            }
            joints.push(j);
        }
        body.entries.push(("velocity".into(), ints(v)));
        body.entries.push(("angular_velocity".into(), ints(w)));
        tables.push(root);
        tables.push(body);
        for _ in 0..n {
            let nrm = small_dir(r);
            let p = vec3(r);
            tables.push(contact(r, p, Some(nrm)));
        }
        if !cons.entries.is_empty() {
            tables.push(cons);
        }
        tables.extend(joints);
    } else {
        // A sphere of radius 5 or an ellipsoid, points on it with rational coordinates.
        let (f, pts): (&str, &[[i64; 3]]) = if r.chance(0.5) {
            (
                "x^2 + y^2 + z^2 - 25",
                &[
                    [3, 4, 0],
                    [0, -3, 4],
                    [5, 0, 0],
                    [0, 0, -5],
                    [-4, 0, 3],
                    [0, 5, 0],
                ],
            )
        } else {
            (
                "x^2/1 + y^2/4 + z^2/9 - 1",
                &[[1, 0, 0], [0, 2, 0], [0, 0, 3], [-1, 0, 0], [0, 0, -3]],
            )
        };
        n = r.int(1, 3) as usize;
        body.entries.push(("velocity".into(), vec3(r)));
        body.entries.push(("angular_velocity".into(), vec3(r)));
        tables.push(root);
        tables.push(body);
        tables.push(Table {
            header: Some("surface".into()),
            entries: vec![("f".into(), format!("\"{f}\""))],
        });
        for _ in 0..n {
            let p = *r.pick(pts);
            let normal = if r.chance(0.2) { Some(p) } else { None };
            tables.push(contact(r, ints(p), normal));
        }
    }
    if r.chance(0.5) {
        let mut s = Table {
            header: Some("solve".into()),
            entries: vec![],
        };
        if r.chance(0.7) {
            let m = *r.pick(&["[\"newton\"]", "[\"poisson\"]", "[\"newton\", \"poisson\"]"]);
            s.entries.push(("models".into(), m.into()));
        }
        if r.chance(0.4) {
            let l = *r.pick(&["\"simultaneous\"", "\"unilateral\""]);
            s.entries.push(("law".into(), l.into()));
        }
        tables.push(s);
    }
    let vary = r
        .pick(&[
            "contact[0].k=0:1:3",
            "body.mass=1:2:3",
            "body.velocity[0]=-1:1:3",
            "body.angular_velocity[2]=0:1:2",
            "contact[0].point[1]=-1:1:3",
            "body.mass=1e-400:1:2",
            "body.mass=1:1e308:2",
            "contact[0].k=0:1.5:3",
            "body.inertia[0]=\"2^-99999\":1:2",
            "contact[9].k=0:1:2",
        ])
        .to_string();
    Case {
        tables,
        symbols: vec![],
        vary,
        contacts: n,
        mutations: vec![],
        raw: None,
    }
}

/// Replace the numbers of a small scene by symbols (for `derive`).
fn symbolise(r: &mut Rng, c: &mut Case) {
    let names = ["m", "Jx", "Jz", "k1", "k2", "a", "omega", "theta"];
    let mut used = vec![];
    for s in c.slots() {
        if !r.chance(0.25) {
            continue;
        }
        let v = &c.tables[s.0].entries[s.1].1;
        let key = c.tables[s.0].entries[s.1].0.clone();
        if key == "kind" || key == "f" || key == "name" || key == "models" || key == "law" {
            continue;
        }
        let sym = *r.pick(&names);
        if matches!(
            key.as_str(),
            "normal" | "tangent" | "point" | "velocity" | "angular_velocity"
        ) {
            c.mutations.push("symbolic axis".into());
        }
        let new = if v.starts_with('[') && !v.starts_with("[[") {
            let parts: Vec<&str> = v
                .trim_matches(|ch| ch == '[' || ch == ']')
                .split(',')
                .collect();
            let i = r.below(parts.len());
            let mut p: Vec<String> = parts.iter().map(|x| x.trim().to_string()).collect();
            p[i] = if sym == "theta" {
                format!("\"cos({sym})\"")
            } else {
                format!("\"{sym}\"")
            };
            format!("[{}]", p.join(", "))
        } else if v.starts_with('[') {
            continue;
        } else {
            format!("\"{sym}\"")
        };
        c.tables[s.0].entries[s.1].1 = new;
        used.push(sym.to_string());
    }
    used.sort();
    used.dedup();
    if r.chance(0.1) {
        used.pop(); // an undeclared symbol
    }
    if r.chance(0.05) {
        used.push(r.pick(&["pi", "sqrt", "1x", "nan", "x y"]).to_string());
    }
    if used.is_empty() {
        used.push("m".into());
    }
    c.symbols = used;
    c.mutations.push("symbols".into());
}

/// Replace one element of an array value (or the scalar) by `new`.
fn replace_in(r: &mut Rng, v: &str, new: &str) -> String {
    if v.starts_with('[') && !v.starts_with("[[") && v.contains(',') {
        let parts: Vec<&str> = v
            .trim_matches(|ch| ch == '[' || ch == ']')
            .split(',')
            .collect();
        let i = r.below(parts.len());
        let mut p: Vec<String> = parts.iter().map(|x| x.trim().to_string()).collect();
        p[i] = new.to_string();
        format!("[{}]", p.join(", "))
    } else {
        new.to_string()
    }
}

fn mutate(r: &mut Rng, c: &mut Case) {
    let slots = c.slots();
    let contacts = c.contact_tables();
    let what = r.below(16);
    let label;
    match what {
        0..=4 if !slots.is_empty() => {
            let (t, j) = *r.pick(&slots);
            let x = *r.pick(EXTREMES);
            let old = c.tables[t].entries[j].1.clone();
            c.tables[t].entries[j].1 = replace_in(r, &old, x);
            label = format!("extreme {} ← {x}", c.tables[t].entries[j].0);
        }
        5 if !slots.is_empty() => {
            let (t, j) = *r.pick(&slots);
            let (k, _) = c.tables[t].entries.remove(j);
            label = format!("dropped {k}");
        }
        6 if !slots.is_empty() => {
            let (t, j) = *r.pick(&slots);
            let e = c.tables[t].entries[j].clone();
            label = format!("duplicated {}", e.0);
            c.tables[t].entries.push(e);
        }
        7 => {
            let t = r.below(c.tables.len());
            let k = *r.pick(&["\"\"", "bogus", "\"with space\"", "Mass", "normals", "k1"]);
            c.tables[t].entries.push((k.to_string(), "1".into()));
            label = format!("unknown key {k}");
        }
        8 if !slots.is_empty() => {
            let (t, j) = *r.pick(&slots);
            let w = *r.pick(WRONG);
            c.tables[t].entries[j].1 = w.to_string();
            label = format!("wrong type {} ← {w}", c.tables[t].entries[j].0);
        }
        9 if !contacts.is_empty() => {
            let t = *r.pick(&contacts);
            let z = *r.pick(&[
                "[0, 0, 0]",
                "[0.0, -0.0, 0]",
                "[\"1e-400\", 0, 0]",
                "[5e-324, 0, 0]",
            ]);
            let key = *r.pick(&["normal", "tangent"]);
            c.set(t, key, z.into());
            label = format!("zero {key}");
        }
        10 if contacts.len() >= 2 => {
            let a = contacts[0];
            let b = contacts[1];
            let key = *r.pick(&["point", "normal"]);
            if let Some(j) = c.get(a, key) {
                let v = c.tables[a].entries[j].1.clone();
                c.set(b, key, v);
            }
            label = format!("coincident/parallel {key}");
        }
        11 if !contacts.is_empty() => {
            let t = *r.pick(&contacts);
            c.set(t, "normal", "[1, 0, 0]".into());
            let tan = *r.pick(&[
                "[1, 1, 0]",
                "[1, 0, 0]",
                "[0, 1, 1e-30]",
                "[0, \"1e-300\", 0]",
            ]);
            c.set(t, "tangent", tan.into());
            label = "tangent not perpendicular".into();
        }
        12 => {
            let s = match c
                .tables
                .iter()
                .position(|t| t.header.as_deref() == Some("solve"))
            {
                Some(s) => s,
                None => {
                    c.tables.push(Table {
                        header: Some("solve".into()),
                        entries: vec![],
                    });
                    c.tables.len() - 1
                }
            };
            let (k, v) = *r.pick(&[
                ("models", "[]"),
                ("models", "[\"newton\", \"newton\"]"),
                ("models", "[\"euler\"]"),
                ("models", "\"newton\""),
                ("law", "\"unilateral\""),
                ("law", "\"bilateral\""),
                ("law", "1"),
                ("models", "[\"poisson\", \"newton\"]"),
            ]);
            c.set(s, k, v.into());
            label = format!("solve.{k} = {v}");
        }
        13 => {
            let (h, k, v) = *r.pick(&[
                ("surface", "f", "\"x^2 + y^2 + z^2 - 25\""),
                ("surface", "f", "\"x^2 + y^2 + z^2 + 1\""),
                ("surface", "f", "\"x*y*z\""),
                ("surface", "f", "\"x^\""),
                ("surface", "f", "\"w + 1\""),
                ("surface", "f", "\"1 - x^2 - y^2 - z^2\""),
                ("surface", "g", "1"),
                ("constraints", "free", "[[0, 0, 0, 0, 0, 0]]"),
                ("constraints", "free", "[[1, 0, 0, 0, 0, 0], [1, 0, 0, 0, 0, 0]]"),
                ("constraints", "free", "[[1, 0, 0, 0, 0]]"),
                ("constraints", "blocked", "[[1, 0, 0, 0, 0, 0]]"),
                ("constraints", "free", "[[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0], [0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 0, 0, 0, 1]]"),
                ("constraints", "free", "[]"),
            ]);
            let t = match c.tables.iter().position(|t| t.header.as_deref() == Some(h)) {
                Some(t) => t,
                None => {
                    c.tables.push(Table {
                        header: Some(h.into()),
                        entries: vec![],
                    });
                    c.tables.len() - 1
                }
            };
            c.set(t, k, v.into());
            label = format!("{h}.{k} = {v}");
        }
        14 => {
            let (kind, extra) = *r.pick(&[
                ("revolute", "axis = [0, 0, 0]"),
                ("revolute", "point = [0, 0, 0]"),
                ("hinge", "axis = [0, 0, 1]"),
                ("planar", "normal = [0, 0, 1]"),
                ("prismatic", "axis = [1, 0, 0]"),
                ("spherical", "point = [1, 2, 3]"),
                ("cylindrical", "axis = [0, 1, 0]\npoint = [1e308, 0, 0]"),
            ]);
            let mut entries = vec![("kind".to_string(), format!("\"{kind}\""))];
            for line in extra.lines() {
                let (k, v) = line.split_once(" = ").unwrap();
                entries.push((k.into(), v.into()));
            }
            c.tables.push(Table {
                header: Some("[constraints.joint]".into()),
                entries,
            });
            label = format!("joint {kind} {extra}");
        }
        _ => {
            let len = c.render().len();
            let at = r.below(len.max(1));
            let ch = if r.chance(0.5) {
                None
            } else {
                Some(*r.pick(&['\u{0}', '"', '[', '=', '\n', 'é', '\u{202e}', '#']))
            };
            c.raw = Some((at, ch));
            label = format!("raw {at} {ch:?}");
        }
    }
    c.mutations.push(label);
}

/// Case number `i` of the run seeded with `seed`.
pub fn case(seed: u64, i: u64) -> Case {
    let mut r = Rng::new(seed ^ i.wrapping_mul(0xA076_1D64_78BD_642F));
    let mut c = base(&mut r);
    if c.contacts <= 3 && r.chance(0.12) {
        symbolise(&mut r, &mut c);
    }
    // A fifth stay valid; the rest get 1–3 mutations.
    if !r.chance(0.2) {
        for _ in 0..r.int(1, 3) {
            mutate(&mut r, &mut c);
        }
    }
    if c.symbols.is_empty() && r.chance(0.3) {
        c.symbols = vec!["m".into(), "k1".into()];
    }
    c
}
