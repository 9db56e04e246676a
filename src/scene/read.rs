//! Reading a scene document: the walk from the top-level keys down to each table, and the
//! reader's primitives (required keys, numbers as written, range checks), each turning a
//! problem into a [`SceneError`] that names the key path and the value.

use crate::impact::unilateral::Law;
use num_traits::Signed;
use toml_edit::{DocumentMut, Item, Table, TableLike, Value};

use super::model::{self, params::Params};
use super::schema::ContactSpec;
use super::{Scene, SceneError};
use crate::number::Number;

/// Parse TOML text into a document (syntax errors name the file and the position).
pub fn parse_document(text: &str, file: &str) -> Result<DocumentMut, SceneError> {
    text.parse::<DocumentMut>().map_err(|e| SceneError {
        file: file.to_string(),
        key: String::new(),
        value: None,
        message: format!("not valid TOML: {}", e.to_string().trim()),
    })
}

/// Read and validate a scene document; `file` names it in messages, `symbols` are the names
/// values may use.
pub(super) fn scene(
    doc: &DocumentMut,
    file: &str,
    symbols: &[String],
    seed: Option<&str>,
) -> Result<Scene, SceneError> {
    let root = doc.as_table();
    let r = Reader {
        file,
        symbols,
        params: Params::new(symbols, seed),
        observed: Default::default(),
        lowest: Default::default(),
    };
    r.only_keys(root, "", TOP_KEYS)?;
    let r = Reader {
        params: r.params(root, seed)?,
        ..r
    };
    let name = r.name(root)?;
    let several = model::system::declared(root);
    if !several && let Some(joint) = root.get("joint") {
        return Err(r.err(
            "joint",
            Some(short(joint)),
            "[[joint]] tables join the bodies of a scene of several [[body]] tables; one body's \
             joints to the ground are `[[constraints.joint]]`",
        ));
    }
    let modelled = !several && model::declared(root);
    // The paper's body first, as it was always read (messages name its keys first).
    let classic = if modelled || several {
        None
    } else {
        Some(r.body(root)?)
    };
    let mut contacts = r.contacts(root)?;
    let solve = r.solve(root)?;
    let (models, law, restitution, outputs) =
        (solve.models, solve.law, solve.restitution, solve.outputs);
    if law == Law::Lzb {
        super::law::lzb_allowed(file, restitution, "`[solve] law = \"lzb\"`")?;
    }
    let mut constraints = match root.get("constraints") {
        None => None,
        Some(item) => Some(r.constraints(item)?),
    };
    let mut system = None;
    let (body, axes) = match classic {
        Some(body) => (body, None),
        None if several => {
            let spec = r.system(root, &mut contacts)?;
            // The first body stands in the one-body fields, which a system's solve does not read.
            let first = &spec.bodies[0];
            let body = super::schema::BodyTable {
                mass: first.mass.clone(),
                inertia: first.inertia.clone(),
                inertia_products: first.inertia_products.clone(),
                velocity: first.velocity.clone(),
                angular_velocity: first.angular_velocity.clone(),
            };
            system = Some(spec);
            (body, Some(model::Axes::World))
        }
        None => {
            let lowered = r.lower(root, &mut contacts, &mut constraints)?;
            (lowered.body, Some(lowered.axes))
        }
    };
    let surface = match root.get("surface") {
        None => None,
        Some(item) => Some(r.surface(item)?),
    };
    Ok(Scene {
        file: file.to_string(),
        name,
        mass: body.mass,
        inertia: body.inertia,
        inertia_products: body.inertia_products,
        velocity: body.velocity,
        angular_velocity: body.angular_velocity,
        contacts,
        models,
        law,
        restitution,
        outputs,
        tolerance: solve.tolerance,
        constraints,
        surface,
        params: r.params.specs(),
        axes,
        angles: r.observed.borrow().angles.clone(),
        density: r.observed.borrow().density.clone(),
        system,
    })
}

impl Reader<'_> {
    /// `[params]`: each name = a value, read in order (a value may use the names above it);
    /// `seed` must name one of them.
    fn params(&self, root: &Table, seed: Option<&str>) -> Result<Params, SceneError> {
        let mut params = Params::new(self.symbols, seed);
        if let Some(item) = root.get("params") {
            let t = item.as_table_like().ok_or_else(|| {
                self.err(
                    "params",
                    Some(short(item)),
                    "must be a table: [params] name = value",
                )
            })?;
            for (name, v) in t.iter() {
                let key = format!("params.{name}");
                if let Some(why) = params.refuse_name(name) {
                    return Err(self.err(&key, Some(short(v)), why));
                }
                let text = match v.as_value() {
                    Some(Value::Integer(f)) => f.display_repr().into_owned(),
                    Some(Value::Float(f)) => f.display_repr().into_owned(),
                    Some(Value::String(s)) => s.value().clone(),
                    _ => {
                        return Err(self.err(
                            &key,
                            Some(short(v)),
                            "must be a number or an expression string",
                        ));
                    }
                };
                params.push(name, &text).map_err(|e| {
                    let mut message = e.to_string();
                    if let Some(hint) = degree_hint(&text) {
                        message += &hint;
                    }
                    if message.contains("unknown name") {
                        message += "; a parameter may use only the parameters above it";
                    }
                    self.err(&key, Some(short(v)), message)
                })?;
            }
        }
        if let Some(s) = seed
            && !params.specs().iter().any(|p| p.name == s)
        {
            let names: Vec<String> = params.specs().into_iter().map(|p| p.name).collect();
            return Err(self.err(
                &format!("params.{s}"),
                None,
                format!(
                    "no such parameter; [params] has: {}",
                    if names.is_empty() {
                        "none".into()
                    } else {
                        names.join(", ")
                    }
                ),
            ));
        }
        Ok(params)
    }

    /// The scene's `name` (the file name when absent); `description` must be a string.
    fn name(&self, root: &Table) -> Result<String, SceneError> {
        let file = self.file;
        let name = match root.get("name") {
            None => file.rsplit('/').next().unwrap_or(file).to_string(),
            Some(item) => self.string(item, "name")?,
        };
        if let Some(item) = root.get("description") {
            self.string(item, "description")?;
        }
        Ok(name)
    }

    /// The `[[contact]]` tables, at least one.
    fn contacts(&self, root: &Table) -> Result<Vec<ContactSpec>, SceneError> {
        let contacts = match root.get("contact") {
            Some(Item::ArrayOfTables(arr)) => arr
                .iter()
                .enumerate()
                .map(|(i, t)| self.contact(t, i))
                .collect::<Result<Vec<_>, _>>()?,
            Some(other) => {
                return Err(self.err("contact", Some(short(other)), "must be [[contact]] tables"));
            }
            None => Vec::new(),
        };
        if contacts.is_empty() {
            return Err(self.err("contact", None, "a scene needs at least one [[contact]]"));
        }
        Ok(contacts)
    }
}

/// An item as written, cut to 60 characters, for messages.
pub(super) fn short(item: &Item) -> String {
    let s = item.to_string();
    let s = s.trim();
    if s.len() > 60 {
        format!("{}…", &s[..s.floor_char_boundary(60)])
    } else {
        s.to_string()
    }
}

/// The keys a scene may have at its top level.
const TOP_KEYS: &[&str] = &[
    "name",
    "description",
    "params",
    "body",
    "obstacle",
    "contact",
    "solve",
    "constraints",
    "surface",
    "joint",
];

/// Whether a value in symbols is identically zero (`"m - m"`).
fn symbolic_zero(n: &Number) -> bool {
    crate::scalar::symbolic::symbolic(&n.text, &n.symbols)
        .is_ok_and(|x| num_traits::Zero::is_zero(&x))
}

/// Reads values out of a document, turning every problem into a [`SceneError`].
pub(super) struct Reader<'a> {
    /// The file, for messages.
    file: &'a str,
    /// Names values may use as symbols.
    pub(super) symbols: &'a [String],
    /// The scene's `[params]`, substituted into every value.
    pub(super) params: Params,
    /// What the reading saw that the scene keeps for its notes and messages.
    pub(super) observed: std::cell::RefCell<Observed>,
    /// A box's touching corners found so far ([`model::LowestCorners`]).
    pub(super) lowest: model::LowestCorners,
}

/// What reading a scene saw besides its values: the pose angles (for the radian note and the
/// exact solver's refusals, which name them) and the density a shape and a mass give (for the
/// units note).
#[derive(Default)]
pub(super) struct Observed {
    /// Each pose angle: its key and its value as read.
    pub(super) angles: Vec<(String, Number)>,
    /// The density m / V of each shape given its mass, in kg/m³, as a number, with the key of
    /// its body (`body`, or `body[i]` in a system).
    pub(super) density: Vec<(String, f64)>,
}

impl Reader<'_> {
    /// A [`SceneError`] at `key`.
    pub(super) fn err(
        &self,
        key: &str,
        value: Option<String>,
        message: impl Into<String>,
    ) -> SceneError {
        SceneError {
            file: self.file.to_string(),
            key: key.to_string(),
            value,
            message: message.into(),
        }
    }

    /// Refuse a key of `t` (at path `at`) that is not `known`.
    pub(super) fn only_keys(
        &self,
        t: &dyn TableLike,
        at: &str,
        known: &[&str],
    ) -> Result<(), SceneError> {
        for (k, v) in t.iter() {
            if !known.contains(&k) {
                // An empty or odd key is shown as TOML writes it (`""`), never as nothing.
                let k = if k.is_empty()
                    || k.contains(|c: char| !(c.is_alphanumeric() || c == '_' || c == '-'))
                {
                    format!("{k:?}")
                } else {
                    k.to_string()
                };
                let key = if at.is_empty() {
                    k
                } else {
                    format!("{at}.{k}")
                };
                return Err(self.err(
                    &key,
                    Some(short(v)),
                    format!("unknown key; expected one of: {}", known.join(", ")),
                ));
            }
        }
        Ok(())
    }

    /// A required key of a table.
    pub(super) fn get<'t>(
        &self,
        t: &'t dyn toml_edit::TableLike,
        key: &str,
        at: &str,
    ) -> Result<&'t Item, SceneError> {
        t.get(key)
            .ok_or_else(|| self.err(&format!("{at}.{key}"), None, "missing (required)"))
    }

    /// A required sub-table.
    pub(super) fn table<'t>(
        &self,
        t: &'t Table,
        key: &str,
        at: &str,
    ) -> Result<&'t Table, SceneError> {
        let path = if at.is_empty() {
            key.to_string()
        } else {
            format!("{at}.{key}")
        };
        match t.get(key) {
            None => Err(self.err(
                &path,
                None,
                format!("missing (required): add a [{path}] table"),
            )),
            Some(item) => item.as_table().ok_or_else(|| {
                self.err(
                    &path,
                    Some(short(item)),
                    format!("must be a table: [{path}]"),
                )
            }),
        }
    }

    /// A string value.
    pub(super) fn string(&self, item: &Item, key: &str) -> Result<String, SceneError> {
        item.as_str()
            .map(str::to_string)
            .ok_or_else(|| self.err(key, Some(short(item)), "must be a string"))
    }

    /// A number: a TOML integer or float, or a string with a fraction or an expression.
    pub(super) fn number_value(&self, v: &Value, key: &str) -> Result<Number, SceneError> {
        self.number_at(v, &|| key.to_string())
    }

    /// [`Reader::number_value`] with the key formed only for an error: a scene of 10⁵
    /// contacts reads 10⁶ numbers, and formatting each one's key and value text up front
    /// cost about as much as reading it.
    fn number_at(&self, v: &Value, key: &dyn Fn() -> String) -> Result<Number, SceneError> {
        let text: String = match v {
            Value::Integer(f) => f.display_repr().into_owned(),
            Value::Float(f) => f.display_repr().into_owned(),
            Value::String(s) => s.value().clone(),
            other => {
                return Err(self.err(
                    &key(),
                    Some(other.to_string().trim().to_string()),
                    "must be a number (or a string such as \"1/3\")",
                ));
            }
        };
        self.params.number(&text).map_err(|e| {
            let shown = v.to_string().trim().to_string();
            let mut message = e.to_string();
            if self.symbols.is_empty() && message.contains("unknown name") {
                message += "; a symbolic scene is for `inertance derive SCENE --symbols NAME,…`";
            }
            if let Some(hint) = degree_hint(&text) {
                message += &hint;
            }
            self.err(&key(), Some(shown), message)
        })
    }

    /// A number item.
    pub(super) fn number(&self, item: &Item, key: &str) -> Result<Number, SceneError> {
        match item.as_value() {
            Some(v) => self.number_value(v, key),
            None => Err(self.err(key, Some(short(item)), "must be a number")),
        }
    }

    /// An array of three numbers.
    pub(super) fn triple(&self, item: &Item, key: &str) -> Result<[Number; 3], SceneError> {
        let arr = item.as_array().filter(|a| a.len() == 3).ok_or_else(|| {
            self.err(
                key,
                Some(short(item)),
                "must be an array of three numbers [x, y, z]",
            )
        })?;
        let mut out = Vec::with_capacity(3);
        for (i, v) in arr.iter().enumerate() {
            out.push(self.number_at(v, &|| format!("{key}[{i}]"))?);
        }
        let [a, b, c]: [Number; 3] = out
            .try_into()
            .map_err(|_| self.err(key, None, "must have three numbers"))?;
        Ok([a, b, c])
    }

    /// Refuse a value that is not > 0 (`why` says what it is).
    pub(super) fn positive(&self, n: &Number, key: &str, why: &str) -> Result<(), SceneError> {
        if let Err(reason) = &n.exact
            && n.symbols.is_empty()
            && n.approx == 0.0
        {
            // No exact value (too many bits) and an f64 that underflowed: its sign is unknown,
            // and "must be positive" would be wrong.
            return Err(self.err(
                key,
                Some(n.text.clone()),
                format!("{reason}, and its f64 value underflows to 0: the number cannot be read"),
            ));
        }
        let ok = match &n.exact {
            Ok(q) => q.is_positive(),
            // A symbolic value's sign is the reader's assumption, but not when it is 0.
            Err(_) if !n.symbols.is_empty() => !symbolic_zero(n),
            Err(_) => n.approx > 0.0,
        };
        if ok {
            Ok(())
        } else {
            Err(self.err(key, Some(n.text.clone()), format!("{why} (> 0)")))
        }
    }

    /// Refuse a coefficient of restitution outside [0, 1].
    pub(super) fn coefficient(&self, n: Number, key: &str) -> Result<Number, SceneError> {
        let ok = match &n.exact {
            Ok(q) => !q.is_negative() && *q <= num_traits::One::one(),
            Err(_) => !n.symbols.is_empty() || (0.0..=1.0).contains(&n.approx),
        };
        if ok {
            Ok(n)
        } else {
            Err(self.err(
                key,
                Some(n.text.clone()),
                "a coefficient of restitution must lie in [0, 1]",
            ))
        }
    }

    /// Refuse a negative coefficient of friction.
    pub(super) fn friction(&self, n: Number, key: &str) -> Result<Number, SceneError> {
        let ok = match &n.exact {
            Ok(q) => !q.is_negative(),
            Err(_) => !n.symbols.is_empty() || n.approx >= 0.0,
        };
        if ok {
            Ok(n)
        } else {
            Err(self.err(
                key,
                Some(n.text.clone()),
                "a coefficient of friction must not be negative (0: frictionless)",
            ))
        }
    }

    /// Refuse the zero vector (`what` names it).
    pub(super) fn nonzero(&self, t: &[Number; 3], key: &str, what: &str) -> Result<(), SceneError> {
        let zero = t.iter().all(|n| match &n.exact {
            Ok(q) => num_traits::Zero::is_zero(q),
            Err(_) if !n.symbols.is_empty() => symbolic_zero(n),
            Err(_) => n.approx == 0.0,
        });
        if zero {
            let shown = format!("[{}, {}, {}]", t[0].text, t[1].text, t[2].text);
            Err(self.err(
                key,
                Some(shown),
                format!("{what} must not be the zero vector"),
            ))
        } else {
            Ok(())
        }
    }
}

/// "3°" or "3 degrees" for an angle: the grammar's unit is `deg` (a bare number is radians).
fn degree_hint(text: &str) -> Option<String> {
    let lower = text.to_ascii_lowercase();
    let at = lower.find('°').or_else(|| lower.find("degree"))?;
    let before = text[..at].trim_end();
    let start = before
        .rfind(|c: char| !(c.is_ascii_digit() || c == '.'))
        .map_or(0, |i| i + 1);
    let number = &before[start..];
    let number = if number.is_empty() { "30" } else { number };
    Some(format!(
        "; did you mean `{number} deg`? (angles are written with `deg`; a bare number is radians)"
    ))
}

/// Read the exact sphere of a scene to simulate ([`super::model::exact_sphere`]), given its
/// setup as [`simulation`] read it.
pub(super) fn exact_sphere<T: crate::scalar::Scalar>(
    doc: &DocumentMut,
    file: &str,
    setup: &crate::simulate::Setup,
) -> Result<crate::simulate::exact::ExactSphere<T>, SceneError> {
    let root = doc.as_table();
    let r = Reader {
        file,
        symbols: &[],
        params: Params::new(&[], None),
        observed: Default::default(),
        lowest: Default::default(),
    };
    let r = Reader {
        params: r.params(root, None)?,
        ..r
    };
    r.exact_sphere(root, setup)
}

/// Read a scene to simulate ([`super::model::simulation`], or of several `[[body]]`
/// [`super::model::simulated_system`]): its name and what to run.
pub(super) fn simulation(doc: &DocumentMut, file: &str) -> Result<(String, Simulated), SceneError> {
    let root = doc.as_table();
    let r = Reader {
        file,
        symbols: &[],
        params: Params::new(&[], None),
        observed: Default::default(),
        lowest: Default::default(),
    };
    let mut keys: Vec<&str> = TOP_KEYS.to_vec();
    keys.push("simulate");
    r.only_keys(root, "", &keys)?;
    let r = Reader {
        params: r.params(root, None)?,
        ..r
    };
    let name = r.name(root)?;
    if model::system::declared(root) {
        return Ok((name, Simulated::System(Box::new(r.simulated_system(root)?))));
    }
    Ok((name, Simulated::Body(Box::new(r.simulation(root)?))))
}

/// What a scene to simulate runs.
#[derive(Clone, Debug, PartialEq)]
pub enum Simulated {
    /// One body.
    Body(Box<crate::simulate::Setup>),
    /// Several bodies.
    System(Box<crate::simulate::system::SystemSetup>),
}
