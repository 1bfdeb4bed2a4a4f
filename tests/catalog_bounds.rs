//! Every bound the catalogue declares is enforced, with a located error.
//!
//! The test walks every keyword of every command of the registry (inside
//! factor keywords and conditional blocks too) and, for each declared
//! bound, writes a small command file that breaks it on a line of its own:
//! a value below `val_min` or above `val_max`, a value outside `into`, one
//! value too many or one too few (an empty tuple where a value is
//! required), a value of the wrong type, a required keyword left out or
//! given as `None`, a factor keyword with too many occurrences or none
//! (`KEY=()`), and each rule (UN_PARMI, AU_MOINS_UN, EXCLUS, ENSEMBLE,
//! PRESENT_PRESENT, PRESENT_ABSENT) violated. The checker must report an
//! error naming the keyword at the line of the malformed text. Other
//! errors in the generated file (keywords the generator leaves out) are
//! allowed: only the expected one is looked for.
//!
//! Cases the generator cannot build are counted as skipped with their
//! reason; the test prints the totals and fails if a bound is not
//! enforced or if the skipped cases grow beyond a few.

use std::collections::BTreeMap;

use aster::catalog::checker::check_program;
use aster::catalog::schema::{
    CommandSpec, Cond, Factor, Keyword, Lit, Produces, Rule, Simple, Status, Ty,
};
use aster::concepts::ConceptType;
use aster::diag::{Severity, Source};

/// A keyword=value line of the generated file.
#[derive(Clone, Debug)]
struct Item {
    key: String,
    value: Value,
}

#[derive(Clone, Debug)]
enum Value {
    /// Literal Python text on one line.
    Text(String),
    /// `_F(...)` with its own items, one per line.
    Fact(Vec<Item>),
}

/// Where the malformed text is: the keyword path the error must name and
/// the marker that identifies its line.
struct Expect {
    keyword: Option<String>,
    fragment: &'static str,
}

const MARK: &str = "#<<";

/// One malformed file.
struct Case {
    what: String,
    text: String,
    expect: Expect,
}

/// The names bound to one concept of each type by the prelude.
struct Prelude {
    text: String,
    names: BTreeMap<String, String>,
}

fn type_key(t: ConceptType) -> String {
    t.aster_name().to_string()
}

fn prelude(specs: &[&CommandSpec]) -> Prelude {
    let mut text = String::from("DEBUT()\n");
    let mut names = BTreeMap::new();
    for s in specs {
        // (type, the call's keywords): a ByText command (CREA_CHAMP) makes
        // each of its types with a value of its key that selects it.
        let mut made: Vec<(ConceptType, String)> = Vec::new();
        match s.produces {
            Produces::Concept(t) => made.push((t, String::new())),
            Produces::ByText(key, table, default) => {
                made.push((default, String::new()));
                for (prefix, t) in table {
                    let value = s.keywords.iter().find_map(|k| match k {
                        Keyword::Simple(x) if x.name == key => x.into.as_ref().and_then(|v| {
                            v.iter().find_map(|l| match l {
                                Lit::Text(t) if t.starts_with(prefix) => Some(t.to_string()),
                                _ => None,
                            })
                        }),
                        _ => None,
                    });
                    if let Some(v) = value {
                        made.push((*t, format!("{key}='{v}'")));
                    }
                }
            }
            _ => {}
        }
        for (t, kws) in made {
            if !names.contains_key(&type_key(t)) {
                let name = format!("C_{}", names.len());
                // The producing call may miss keywords: the checker still
                // binds the name to its type, which is all a case needs.
                text.push_str(&format!("{name} = {}({kws})\n", s.name));
                names.insert(type_key(t), name);
            }
        }
    }
    Prelude { text, names }
}

fn lit_text(l: &Lit) -> String {
    match l {
        Lit::Int(i) => i.to_string(),
        Lit::Real(r) => format!("{r:?}"),
        Lit::Text(t) => format!("'{t}'"),
    }
}

fn real_text(x: f64) -> String {
    format!("{x:?}")
}

/// A valid value of a simple keyword, or None when the prelude has no
/// concept of its type.
fn valid(s: &Simple, pre: &Prelude) -> Option<String> {
    if let Some(into) = &s.into {
        return into.first().map(lit_text);
    }
    Some(match &s.ty {
        Ty::Real => real_text(s.val_min.or(s.val_max).unwrap_or(1.0)),
        Ty::Int => {
            let x = s
                .val_min
                .map(f64::ceil)
                .or(s.val_max.map(f64::floor))
                .unwrap_or(1.0);
            format!("{}", x as i64)
        }
        Ty::Text => "'A'".into(),
        Ty::Concept(tys) => tys
            .iter()
            .find_map(|t| pre.names.get(&type_key(*t)).cloned())?,
    })
}

/// A value of another type than the keyword's.
fn wrong_type(s: &Simple) -> String {
    match &s.ty {
        Ty::Real | Ty::Int | Ty::Concept(_) => "'WRONG_TYPE'".into(),
        Ty::Text => "1.5".into(),
    }
}

/// The keywords of one level with the conditions that make each visible.
fn visible<'k>(
    keywords: &'k [Keyword],
    conds: &[&'k Cond],
    out: &mut Vec<(&'k Keyword, Vec<&'k Cond>)>,
) {
    for k in keywords {
        match k {
            Keyword::Block(b) => {
                let mut c = conds.to_vec();
                c.push(&b.condition);
                visible(&b.keywords, &c, out);
            }
            _ => out.push((k, conds.to_vec())),
        }
    }
}

fn find<'k>(level: &[(&'k Keyword, Vec<&'k Cond>)], name: &str) -> Option<&'k Keyword> {
    level.iter().map(|(k, _)| *k).find(|k| k.name() == name)
}

/// Items that make `cond` hold at a level, added to `items`; Err with the
/// reason when the generator cannot satisfy it.
fn satisfy(
    cond: &Cond,
    level: &[(&Keyword, Vec<&Cond>)],
    pre: &Prelude,
    items: &mut Vec<Item>,
    absent: &mut Vec<String>,
) -> Result<(), String> {
    let set = |key: &str, v: String, items: &mut Vec<Item>| -> Result<(), String> {
        if absent.iter().any(|a| a == key) {
            return Err(format!("condition needs {key} both given and absent"));
        }
        match items.iter().find(|i| i.key == key) {
            Some(i) => match &i.value {
                Value::Text(t) if *t == v => Ok(()),
                _ => Err(format!("conditions give {key} two values")),
            },
            None => {
                items.push(Item {
                    key: key.to_string(),
                    value: Value::Text(v),
                });
                Ok(())
            }
        }
    };
    match cond {
        Cond::Eq(k, l) => set(k, lit_text(l), items),
        Cond::In(k, ls) => set(k, lit_text(&ls[0]), items),
        Cond::Present(k) => {
            if items.iter().any(|i| i.key == *k) {
                return Ok(());
            }
            match find(level, k) {
                Some(Keyword::Simple(s)) => {
                    let v = valid(s, pre).ok_or("no concept of the type")?;
                    set(k, v, items)
                }
                Some(Keyword::Factor(_)) => {
                    items.push(Item {
                        key: k.to_string(),
                        value: Value::Fact(Vec::new()),
                    });
                    Ok(())
                }
                _ => Err(format!("condition on unknown keyword {k}")),
            }
        }
        Cond::Absent(k) => {
            if items.iter().any(|i| i.key == *k) {
                return Err(format!("condition needs {k} absent but it is given"));
            }
            absent.push(k.to_string());
            Ok(())
        }
        Cond::And(cs) => {
            for c in cs {
                satisfy(c, level, pre, items, absent)?;
            }
            Ok(())
        }
        Cond::Or(cs) => {
            let mut last = Err("empty OR".to_string());
            for c in cs {
                let (mut i2, mut a2) = (items.clone(), absent.clone());
                last = satisfy(c, level, pre, &mut i2, &mut a2);
                if last.is_ok() {
                    *items = i2;
                    *absent = a2;
                    break;
                }
            }
            last
        }
        Cond::Not(inner) => match inner.as_ref() {
            Cond::Present(k) => satisfy(&Cond::Absent(k), level, pre, items, absent),
            Cond::Absent(k) => satisfy(&Cond::Present(k), level, pre, items, absent),
            // NOT(k == v): give k another allowed value, or leave it out
            // when its default is not v (absent differs from v).
            Cond::Eq(k, l) => not_in(k, std::slice::from_ref(l), level, items),
            Cond::In(k, ls) => not_in(k, ls, level, items),
            _ => Err("NOT of a compound condition".into()),
        },
    }
}

/// Makes keyword `k` take a value outside `ls` (or be absent without a
/// default in the list).
fn not_in(
    k: &str,
    ls: &[Lit],
    level: &[(&Keyword, Vec<&Cond>)],
    items: &mut Vec<Item>,
) -> Result<(), String> {
    let texts: Vec<String> = ls.iter().map(lit_text).collect();
    if let Some(i) = items.iter().find(|i| i.key == k) {
        return match &i.value {
            Value::Text(t) if !texts.contains(t) => Ok(()),
            _ => Err(format!("conditions need {k} in and out of a list")),
        };
    }
    let Some(Keyword::Simple(s)) = find(level, k) else {
        return Err(format!("NOT on unknown keyword {k}"));
    };
    let default_in = s
        .default
        .first()
        .map(lit_text)
        .is_some_and(|d| texts.contains(&d));
    if !default_in {
        return Ok(());
    }
    let other = s
        .into
        .as_ref()
        .and_then(|into| into.iter().map(lit_text).find(|t| !texts.contains(t)))
        .ok_or(format!("no value of {k} outside the list"))?;
    items.push(Item {
        key: k.to_string(),
        value: Value::Text(other),
    });
    Ok(())
}

/// The path from the command to a level: the factor keywords crossed, each
/// with the items its occurrence needs (block conditions) and the rest of
/// the file around it.
#[derive(Clone)]
struct Frame<'k> {
    /// Name of the factor keyword (None for the command level).
    factor: Option<&'k str>,
    /// Items already needed at this level (conditions of the blocks on the
    /// way down, and of the keyword tested).
    items: Vec<Item>,
}

fn render_items(items: &[Item], indent: usize, out: &mut String) {
    for it in items {
        let pad = " ".repeat(indent);
        match &it.value {
            Value::Text(t) => out.push_str(&format!("{pad}{}={t},\n", it.key)),
            Value::Fact(inner) => {
                out.push_str(&format!("{pad}{}=_F(\n", it.key));
                render_items(inner, indent + 4, out);
                out.push_str(&format!("{pad}),\n"));
            }
        }
    }
}

/// The whole file: the prelude, then the command with the frames nested,
/// the innermost frame's items being the tested level.
fn render(pre: &Prelude, spec: &CommandSpec, frames: &[Frame]) -> String {
    // Nest from the innermost level outwards.
    let mut inner: Option<Item> = None;
    for f in frames.iter().rev() {
        let mut items = f.items.clone();
        if let Some(i) = inner.take() {
            items.push(i);
        }
        match f.factor {
            Some(name) => {
                inner = Some(Item {
                    key: name.to_string(),
                    value: Value::Fact(items),
                })
            }
            None => {
                let mut text = pre.text.clone();
                let target = match spec.produces {
                    Produces::Concept(_) | Produces::SameAs(..) | Produces::ByText(..) => "RES = ",
                    Produces::Nothing => "",
                };
                // Marks the level line for errors located at the command.
                text.push_str(&format!("{target}{}(  {MARK}LEVEL0\n", spec.name));
                render_items(&items, 4, &mut text);
                text.push_str(")\nFIN()\n");
                return text;
            }
        }
    }
    unreachable!("the first frame is the command level")
}

/// Builds the cases of one level (a command or a factor keyword's
/// occurrence) and recurses into its factor keywords.
#[allow(clippy::too_many_arguments)]
fn level_cases(
    pre: &Prelude,
    spec: &CommandSpec,
    frames: &[Frame],
    keywords: &[Keyword],
    rules: &[Rule],
    path: &str,
    cases: &mut Vec<Case>,
    skipped: &mut Vec<String>,
) {
    let mut level = Vec::new();
    visible(keywords, &[], &mut level);
    let depth = frames.len() - 1;
    let level_mark = format!("LEVEL{depth}");
    let join = |k: &str| {
        if path.is_empty() {
            k.to_string()
        } else {
            format!("{path}/{k}")
        }
    };
    let base = frames.last().expect("a level").items.clone();
    // Items that make a keyword visible (its blocks' conditions).
    let context = |conds: &[&Cond]| -> Result<(Vec<Item>, Vec<String>), String> {
        let mut items = base.clone();
        let mut absent = Vec::new();
        for c in conds {
            satisfy(c, &level, pre, &mut items, &mut absent)?;
        }
        Ok((items, absent))
    };
    let mut push = |what: String, items: Vec<Item>, expect: Expect| {
        let mut fr = frames.to_vec();
        fr.last_mut().unwrap().items = items;
        cases.push(Case {
            what: format!("{} {what}", spec.name),
            text: {
                // A keyword left out is reported at its level's line.
                let t = render(pre, spec, &fr);
                if t.contains(&format!("{MARK}BAD")) {
                    t
                } else {
                    mark_level(&t, &level_mark)
                }
            },
            expect,
        });
    };

    let mut nested: Vec<Case> = Vec::new();
    for (kw, conds) in &level {
        let name = kw.name();
        let kp = join(name);
        let (ctx, _absent) = match context(conds) {
            Ok(c) => c,
            Err(why) => {
                skipped.push(format!("{} {kp}: {why}", spec.name));
                continue;
            }
        };
        let with = |v: String| -> Vec<Item> {
            let mut items: Vec<Item> = ctx.iter().filter(|i| i.key != name).cloned().collect();
            items.push(Item {
                key: name.to_string(),
                value: Value::Text(format!("{v}  {MARK}BAD")),
            });
            items
        };
        let bad = |fragment| Expect {
            keyword: Some(kp.clone()),
            fragment,
        };
        match kw {
            Keyword::Simple(s) => {
                let Some(ok) = valid(s, pre) else {
                    skipped.push(format!("{} {kp}: no concept of its type", spec.name));
                    continue;
                };
                let int = s.ty == Ty::Int;
                let num = |x: f64| {
                    if int {
                        format!("{}", x as i64)
                    } else {
                        real_text(x)
                    }
                };
                if let Some(lo) = s.val_min {
                    let x = if int {
                        lo.ceil() - 1.0
                    } else {
                        lo - lo.abs().max(1.0)
                    };
                    push(
                        format!("{kp} below val_min"),
                        with(num(x)),
                        bad(if s.into.is_some() {
                            ""
                        } else {
                            "below its minimum"
                        }),
                    );
                }
                if let Some(hi) = s.val_max {
                    let x = if int {
                        hi.floor() + 1.0
                    } else {
                        hi + hi.abs().max(1.0)
                    };
                    push(
                        format!("{kp} above val_max"),
                        with(num(x)),
                        bad(if s.into.is_some() {
                            ""
                        } else {
                            "above its maximum"
                        }),
                    );
                }
                if let Some(into) = &s.into {
                    let v = match (&s.ty, into.first()) {
                        (Ty::Text, _) => "'NOT_IN_LIST'".to_string(),
                        (_, Some(Lit::Int(_))) | (Ty::Int, _) => {
                            let m = into
                                .iter()
                                .filter_map(|l| match l {
                                    Lit::Int(i) => Some(*i),
                                    _ => None,
                                })
                                .max()
                                .unwrap_or(0);
                            (m + 1000).to_string()
                        }
                        _ => "123456.5".to_string(),
                    };
                    push(
                        format!("{kp} outside into"),
                        with(v),
                        bad("is not an allowed value"),
                    );
                }
                if let Some(max) = s.max {
                    let vals = vec![ok.clone(); max + 1].join(", ");
                    push(
                        format!("{kp} {} values for max {max}", max + 1),
                        with(format!("({vals},)")),
                        bad("at most"),
                    );
                }
                if s.min >= 1 {
                    let vals: Vec<String> = vec![ok.clone(); s.min - 1];
                    let t = if vals.is_empty() {
                        "()".to_string()
                    } else {
                        format!("({},)", vals.join(", "))
                    };
                    push(
                        format!("{kp} {} values for min {}", s.min - 1, s.min),
                        with(t),
                        bad("at least"),
                    );
                }
                push(
                    format!("{kp} of the wrong type"),
                    with(wrong_type(s)),
                    bad(""),
                );
                if s.status == Status::Required {
                    let items: Vec<Item> = ctx.iter().filter(|i| i.key != name).cloned().collect();
                    push(
                        format!("{kp} required, left out"),
                        items,
                        Expect {
                            keyword: Some(kp.clone()),
                            fragment: "missing compulsory",
                        },
                    );
                    // Given as None: code_aster reads it as absent.
                    push(
                        format!("{kp} required, given None"),
                        {
                            // Reported at the level's line, as left out.
                            let mut items: Vec<Item> =
                                ctx.iter().filter(|i| i.key != name).cloned().collect();
                            items.push(Item {
                                key: name.to_string(),
                                value: Value::Text("None".into()),
                            });
                            items
                        },
                        Expect {
                            keyword: Some(kp.clone()),
                            fragment: "missing compulsory",
                        },
                    );
                }
            }
            Keyword::Factor(f) => {
                factor_cases(pre, spec, frames, f, &ctx, &kp, &level_mark, &mut push);
                // The occurrence's own level, with the block context above.
                let mut fr = frames.to_vec();
                fr.last_mut().unwrap().items =
                    ctx.iter().filter(|i| i.key != name).cloned().collect();
                fr.push(Frame {
                    factor: Some(f.name),
                    items: Vec::new(),
                });
                level_cases(
                    pre,
                    spec,
                    &fr,
                    &f.keywords,
                    &f.rules,
                    &kp,
                    &mut nested,
                    skipped,
                );
            }
            Keyword::Block(_) => unreachable!("flattened"),
        }
    }
    cases.extend(nested);
    rule_cases(
        pre,
        spec,
        frames,
        &level,
        rules,
        keywords,
        path,
        &level_mark,
        cases,
        skipped,
    );
}

#[allow(clippy::too_many_arguments)]
fn factor_cases(
    _pre: &Prelude,
    _spec: &CommandSpec,
    _frames: &[Frame],
    f: &Factor,
    ctx: &[Item],
    kp: &str,
    _level_mark: &str,
    push: &mut dyn FnMut(String, Vec<Item>, Expect),
) {
    let with = |v: String| -> Vec<Item> {
        let mut items: Vec<Item> = ctx.iter().filter(|i| i.key != f.name).cloned().collect();
        items.push(Item {
            key: f.name.to_string(),
            value: Value::Text(format!("{v}  {MARK}BAD")),
        });
        items
    };
    let bad = |fragment| Expect {
        keyword: Some(kp.to_string()),
        fragment,
    };
    if let Some(max) = f.max {
        let occ = vec!["_F()"; max + 1].join(", ");
        push(
            format!("{kp} {} occurrences for max {max}", max + 1),
            with(format!("({occ},)")),
            bad("at most"),
        );
    }
    if f.min >= 1 {
        push(
            format!("{kp} given as an empty tuple"),
            with("()".into()),
            bad("at least"),
        );
    }
    push(
        format!("{kp} given a plain value"),
        with("1.5".into()),
        bad("factor keyword"),
    );
    if f.status == Status::Required {
        let items: Vec<Item> = ctx.iter().filter(|i| i.key != f.name).cloned().collect();
        push(
            format!("{kp} required, left out"),
            items,
            bad("missing compulsory"),
        );
    }
}

/// The value to give a keyword for a rule case.
fn rule_value(k: &Keyword, pre: &Prelude) -> Option<Value> {
    match k {
        Keyword::Simple(s) => valid(s, pre).map(Value::Text),
        Keyword::Factor(_) => Some(Value::Fact(Vec::new())),
        Keyword::Block(_) => None,
    }
}

fn is_defaulted(level: &[(&Keyword, Vec<&Cond>)], name: &str) -> bool {
    matches!(
        find(level, name),
        Some(Keyword::Simple(Simple {
            status: Status::Defaulted,
            ..
        })) | Some(Keyword::Factor(Factor {
            status: Status::Defaulted,
            ..
        }))
    )
}

#[allow(clippy::too_many_arguments)]
fn rule_cases(
    pre: &Prelude,
    spec: &CommandSpec,
    frames: &[Frame],
    level: &[(&Keyword, Vec<&Cond>)],
    rules: &[Rule],
    keywords: &[Keyword],
    path: &str,
    level_mark: &str,
    cases: &mut Vec<Case>,
    skipped: &mut Vec<String>,
) {
    // Rules of the level and of its blocks (a block's rules apply when
    // its condition holds, which the case then satisfies).
    let mut all: Vec<(&Rule, Vec<&Cond>)> = rules.iter().map(|r| (r, Vec::new())).collect();
    fn block_rules<'k>(
        keywords: &'k [Keyword],
        conds: &[&'k Cond],
        out: &mut Vec<(&'k Rule, Vec<&'k Cond>)>,
    ) {
        for k in keywords {
            if let Keyword::Block(b) = k {
                let mut c = conds.to_vec();
                c.push(&b.condition);
                out.extend(b.rules.iter().map(|r| (r, c.clone())));
                block_rules(&b.keywords, &c, out);
            }
        }
    }
    block_rules(keywords, &[], &mut all);
    let base = frames.last().expect("a level").items.clone();
    for (rule, conds) in all {
        let (kind, ks): (&str, Vec<&str>) = match rule {
            Rule::ExactlyOne(ks) => ("UN_PARMI", ks.clone()),
            Rule::AtLeastOne(ks) => ("AU_MOINS_UN", ks.clone()),
            Rule::Exclusive(ks) => ("EXCLUS", ks.clone()),
            Rule::Together(ks) => ("ENSEMBLE", ks.clone()),
            Rule::IfPresentAllPresent(a, o) => (
                "PRESENT_PRESENT",
                std::iter::once(*a).chain(o.iter().copied()).collect(),
            ),
            Rule::IfPresentAllAbsent(a, o) => (
                "PRESENT_ABSENT",
                std::iter::once(*a).chain(o.iter().copied()).collect(),
            ),
        };
        let label = format!(
            "{} {}{kind}({})",
            spec.name,
            if path.is_empty() {
                String::new()
            } else {
                format!("{path}: ")
            },
            ks.join(", ")
        );
        let mut items = base.clone();
        let mut absent = Vec::new();
        if let Err(why) = conds
            .iter()
            .try_for_each(|c| satisfy(c, level, pre, &mut items, &mut absent))
        {
            skipped.push(format!("{label}: {why}"));
            continue;
        }
        // Violating sets: which of ks to give.
        let defaulted: Vec<&str> = ks
            .iter()
            .copied()
            .filter(|k| is_defaulted(level, k))
            .collect();
        let give: Vec<Vec<&str>> = match rule {
            Rule::ExactlyOne(_) => {
                let mut v = vec![ks[..2.min(ks.len())].to_vec()];
                if defaulted.is_empty() {
                    v.push(Vec::new());
                }
                v
            }
            Rule::AtLeastOne(_) => {
                if !defaulted.is_empty() {
                    skipped.push(format!(
                        "{label}: {} has a default, so the rule always holds",
                        defaulted.join(", ")
                    ));
                    continue;
                }
                vec![Vec::new()]
            }
            Rule::Exclusive(_) => vec![ks[..2].to_vec()],
            Rule::Together(_) => {
                if ks[1..].iter().all(|k| defaulted.contains(k)) {
                    skipped.push(format!(
                        "{label}: the others have defaults, so the rule always holds"
                    ));
                    continue;
                }
                vec![vec![ks[0]]]
            }
            Rule::IfPresentAllPresent(a, o) => {
                if o.iter().all(|k| defaulted.contains(k)) {
                    skipped.push(format!(
                        "{label}: the others have defaults, so the rule always holds"
                    ));
                    continue;
                }
                vec![vec![*a]]
            }
            Rule::IfPresentAllAbsent(a, o) => vec![vec![*a, o[0]]],
        };
        for g in give {
            let mut its: Vec<Item> = items
                .iter()
                .filter(|i| !ks.contains(&i.key.as_str()) || g.contains(&i.key.as_str()))
                .cloned()
                .collect();
            let mut ok = true;
            for k in &g {
                if its.iter().any(|i| i.key == *k) {
                    continue;
                }
                match find(level, k).and_then(|kw| rule_value(kw, pre)) {
                    Some(v) => its.push(Item {
                        key: k.to_string(),
                        value: v,
                    }),
                    None => {
                        skipped.push(format!("{label}: no value for {k}"));
                        ok = false;
                    }
                }
            }
            if !ok {
                continue;
            }
            // Keywords the case must not give but the block conditions set.
            if g.len() < ks.len()
                && items
                    .iter()
                    .any(|i| ks.contains(&i.key.as_str()) && !g.contains(&i.key.as_str()))
            {
                skipped.push(format!(
                    "{label}: a block condition gives a keyword of the rule"
                ));
                continue;
            }
            let mut fr = frames.to_vec();
            fr.last_mut().unwrap().items = its;
            cases.push(Case {
                what: format!("{label} given {{{}}}", g.join(", ")),
                text: render(pre, spec, &fr),
                expect: Expect {
                    keyword: (!path.is_empty()).then(|| path.to_string()),
                    fragment: "",
                },
            });
            // The error is at the level (command or occurrence) line.
            let last = cases.last_mut().unwrap();
            last.text = mark_level(&last.text, level_mark);
        }
    }
}

/// Moves the BAD marker to the line of the level for rule cases: the
/// innermost `_F(` (or the command line at depth 0).
fn mark_level(text: &str, level_mark: &str) -> String {
    if level_mark == "LEVEL0" {
        return text.replace(&format!("{MARK}LEVEL0"), &format!("{MARK}BAD"));
    }
    let depth: usize = level_mark["LEVEL".len()..].parse().unwrap();
    // The occurrence of depth d opens at indent 4 d; it is the last item
    // of its parent level, so the last such line.
    let lines: Vec<&str> = text.lines().collect();
    let target = lines
        .iter()
        .rposition(|l| l.ends_with("=_F(") && l.len() - l.trim_start().len() == 4 * depth)
        .expect("an occurrence line");
    let mut out = String::new();
    for (i, l) in lines.iter().enumerate() {
        out.push_str(l);
        if i == target {
            out.push_str(&format!("  {MARK}BAD"));
        }
        out.push('\n');
    }
    out
}

struct Outcome {
    checked: usize,
    failures: Vec<String>,
}

fn run_case(case: &Case, registry: &[aster::commands::CommandDef]) -> Result<(), String> {
    // The marker is a Python comment: it does not change the file.
    let src = Source::new("bounds.comm", case.text.clone());
    let line = case
        .text
        .lines()
        .position(|l| l.contains(&format!("{MARK}BAD")))
        .map(|i| i + 1)
        .ok_or("no marked line")?;
    let program = match aster::lang::parser::parse(&src) {
        Ok(p) => p,
        Err(d) => return Err(format!("parse error: {}", d.render(Some(&src)))),
    };
    let errors = match check_program(&program, registry) {
        Ok(_) => return Err("accepted".into()),
        Err(ds) => ds,
    };
    let hit = errors.iter().any(|d| {
        d.severity == Severity::Error
            && d.span.is_some_and(|s| src.line_col(s.start).0 == line)
            && (case.expect.keyword.is_none() || d.keyword == case.expect.keyword)
            && d.message.contains(case.expect.fragment)
    });
    if hit {
        Ok(())
    } else {
        let got: Vec<String> = errors
            .iter()
            .map(|d| {
                format!(
                    "  line {:?} [{}] {}",
                    d.span.map(|s| src.line_col(s.start).0),
                    d.keyword.as_deref().unwrap_or("-"),
                    d.message
                )
            })
            .collect();
        Err(format!(
            "no error at line {line} for {:?} containing {:?}; got:\n{}",
            case.expect.keyword,
            case.expect.fragment,
            got.join("\n")
        ))
    }
}

#[test]
fn every_declared_bound_is_enforced_at_the_right_line() {
    let registry = aster::commands::all();
    let specs: Vec<&CommandSpec> = registry.iter().map(|d| &d.spec).collect();
    let pre = prelude(&specs);
    let mut cases = Vec::new();
    let mut skipped = Vec::new();
    for spec in &specs {
        let frames = vec![Frame {
            factor: None,
            items: Vec::new(),
        }];
        level_cases(
            &pre,
            spec,
            &frames,
            &spec.keywords,
            &spec.rules,
            "",
            &mut cases,
            &mut skipped,
        );
    }
    let mut out = Outcome {
        checked: 0,
        failures: Vec::new(),
    };
    for case in &cases {
        match run_case(case, &registry) {
            Ok(()) => out.checked += 1,
            Err(e) => out
                .failures
                .push(format!("{}: {e}\n{}", case.what, case.text)),
        }
    }
    println!(
        "catalogue bounds: {} cases, {} rejected at the right line, {} skipped",
        cases.len(),
        out.checked,
        skipped.len()
    );
    for s in &skipped {
        println!("  skipped: {s}");
    }
    assert!(
        out.failures.is_empty(),
        "{} of {} bounds not enforced:\n{}",
        out.failures.len(),
        cases.len(),
        out.failures
            .iter()
            .take(20)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n\n")
    );
    assert!(cases.len() > 1000, "only {} cases generated", cases.len());
    assert!(skipped.len() <= 20, "{} cases skipped", skipped.len());
}
