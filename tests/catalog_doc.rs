//! The command catalogue: its generated reference is committed and current,
//! and every declaration is well formed (names in rules and conditions
//! exist, no keyword declared twice where both could be active, defaults
//! consistent with types, `into` lists and bounds).

use std::collections::BTreeSet;

use aster::catalog::doc::commands_markdown;
use aster::catalog::schema::*;
use aster::commands;

const DOC_PATH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/commands.md");

#[test]
fn docs_commands_md_is_current() {
    let generated = commands_markdown(&aster::commands::all());
    if std::env::var("UPDATE_DOCS").as_deref() == Ok("1") {
        std::fs::write(DOC_PATH, &generated).expect("write docs/commands.md");
        return;
    }
    let committed = std::fs::read_to_string(DOC_PATH).unwrap_or_default();
    assert!(
        committed == generated,
        "docs/commands.md is stale: run `UPDATE_DOCS=1 cargo test --test catalog_doc`"
    );
}

/// The commands of sdnv103.md section 4, all of which must be declared.
const SDNV103_COMMANDS: &[&str] = &[
    "DEBUT",
    "FIN",
    "LIRE_MAILLAGE",
    "DEFI_GROUP",
    "MODI_MAILLAGE",
    "CREA_MAILLAGE",
    "AFFE_MODELE",
    "DEFI_MATERIAU",
    "AFFE_MATERIAU",
    "AFFE_CHAR_MECA",
    "DEFI_CONTACT",
    "DEFI_CONSTANTE",
    "CREA_CHAMP",
    "DEFI_LIST_REEL",
    "DEFI_LIST_INST",
    "DYNA_NON_LINE",
    "CALC_CHAMP",
    "POST_RELEVE_T",
    "TEST_RESU",
    "TEST_TABLE",
    "IMPR_TABLE",
    "IMPR_RESU",
    "RECU_FONCTION",
    "IMPR_FONCTION",
];

#[test]
fn registry_holds_every_command_once_in_order() {
    let names = commands::names();
    let mut sorted = names.clone();
    sorted.sort_unstable();
    sorted.dedup();
    assert_eq!(
        names, sorted,
        "all() must be alphabetical without duplicates"
    );
    for n in SDNV103_COMMANDS {
        assert!(names.contains(n), "{n} is not in the catalogue");
        assert!(commands::find(n).is_some());
    }
}

// ---------------------------------------------------------------------------
// Well-formedness.

/// One simple or factor keyword declared at a level, with the conditions
/// of the blocks enclosing it (innermost last).
struct Decl<'a> {
    kw: &'a Keyword,
    conds: Vec<&'a Cond>,
}

/// The keywords of one level, looking through blocks.
fn decls<'a>(kws: &'a [Keyword], conds: &[&'a Cond], out: &mut Vec<Decl<'a>>) {
    for k in kws {
        match k {
            Keyword::Block(b) => {
                let mut c = conds.to_vec();
                c.push(&b.condition);
                decls(&b.keywords, &c, out);
            }
            _ => out.push(Decl {
                kw: k,
                conds: conds.to_vec(),
            }),
        }
    }
}

/// The blocks of one level (nested ones included) with their rules.
fn blocks<'a>(kws: &'a [Keyword], out: &mut Vec<&'a Block>) {
    for k in kws {
        if let Keyword::Block(b) = k {
            out.push(b);
            blocks(&b.keywords, out);
        }
    }
}

/// What a condition implies about one keyword, for the exclusivity proof.
#[derive(Debug, Clone)]
enum Fact {
    In(&'static str, Vec<Lit>),
    NotIn(&'static str, Vec<Lit>),
    Present(&'static str),
    Absent(&'static str),
}

fn facts(c: &Cond, out: &mut Vec<Fact>) {
    match c {
        Cond::Eq(k, v) => out.push(Fact::In(k, vec![v.clone()])),
        Cond::In(k, v) => out.push(Fact::In(k, v.clone())),
        Cond::Present(k) => out.push(Fact::Present(k)),
        Cond::Absent(k) => out.push(Fact::Absent(k)),
        Cond::And(v) => v.iter().for_each(|c| facts(c, out)),
        Cond::Not(c) => match c.as_ref() {
            Cond::Eq(k, v) => out.push(Fact::NotIn(k, vec![v.clone()])),
            Cond::In(k, v) => out.push(Fact::NotIn(k, v.clone())),
            Cond::Present(k) => out.push(Fact::Absent(k)),
            Cond::Absent(k) => out.push(Fact::Present(k)),
            _ => {}
        },
        // A disjunction implies `k in (union)` when every branch restricts k.
        Cond::Or(branches) => {
            let per: Vec<Vec<Fact>> = branches
                .iter()
                .map(|b| {
                    let mut f = Vec::new();
                    facts(b, &mut f);
                    f
                })
                .collect();
            if let Some(first) = per.first() {
                for f in first {
                    if let Fact::In(k, _) = f {
                        let mut union = Vec::new();
                        let all = per.iter().all(|fs| {
                            fs.iter().any(|g| match g {
                                Fact::In(k2, v) if k2 == k => {
                                    union.extend(v.iter().cloned());
                                    true
                                }
                                _ => false,
                            })
                        });
                        if all {
                            out.push(Fact::In(k, union));
                        }
                    }
                }
            }
        }
    }
}

fn key_of(f: &Fact) -> &'static str {
    match f {
        Fact::In(k, _) | Fact::NotIn(k, _) | Fact::Present(k) | Fact::Absent(k) => k,
    }
}

/// True when the two facts cannot hold together. `exclusive` lists groups
/// of keywords at most one of which can be present (UN_PARMI, EXCLUS).
fn contradict(a: &Fact, b: &Fact, exclusive: &[Vec<&'static str>]) -> bool {
    use Fact::*;
    let (ka, kb) = (key_of(a), key_of(b));
    if ka != kb {
        let present = |f: &Fact| matches!(f, In(..) | Present(_));
        return present(a)
            && present(b)
            && exclusive.iter().any(|g| g.contains(&ka) && g.contains(&kb));
    }
    match (a, b) {
        (In(_, x), In(_, y)) => !x.iter().any(|v| y.contains(v)),
        (In(_, x), NotIn(_, y)) | (NotIn(_, y), In(_, x)) => x.iter().all(|v| y.contains(v)),
        (In(..) | Present(_), Absent(_)) | (Absent(_), In(..) | Present(_)) => true,
        _ => false,
    }
}

/// Whether two declarations can never be active together.
fn exclusive(a: &Decl, b: &Decl, groups: &[Vec<&'static str>]) -> bool {
    let (mut fa, mut fb) = (Vec::new(), Vec::new());
    a.conds.iter().for_each(|c| facts(c, &mut fa));
    b.conds.iter().for_each(|c| facts(c, &mut fb));
    fa.iter()
        .any(|x| fb.iter().any(|y| contradict(x, y, groups)))
}

fn rule_names(r: &Rule) -> Vec<&'static str> {
    match r {
        Rule::ExactlyOne(k) | Rule::AtLeastOne(k) | Rule::Exclusive(k) | Rule::Together(k) => {
            k.clone()
        }
        Rule::IfPresentAllPresent(a, k) | Rule::IfPresentAllAbsent(a, k) => {
            let mut v = vec![*a];
            v.extend(k);
            v
        }
    }
}

fn cond_names(c: &Cond, out: &mut Vec<&'static str>) {
    match c {
        Cond::Eq(k, _) | Cond::In(k, _) | Cond::Present(k) | Cond::Absent(k) => out.push(k),
        Cond::And(v) | Cond::Or(v) => v.iter().for_each(|c| cond_names(c, out)),
        Cond::Not(c) => cond_names(c, out),
    }
}

fn lit_fits(l: &Lit, ty: &Ty) -> bool {
    matches!(
        (l, ty),
        (Lit::Real(_) | Lit::Int(_), Ty::Real) | (Lit::Int(_), Ty::Int) | (Lit::Text(_), Ty::Text)
    )
}

fn lit_value(l: &Lit) -> Option<f64> {
    match l {
        Lit::Real(r) => Some(*r),
        Lit::Int(i) => Some(*i as f64),
        Lit::Text(_) => None,
    }
}

fn check_simple(s: &Simple, path: &str, errs: &mut Vec<String>) {
    let here = format!("{path}/{}", s.name);
    match s.status {
        Status::Defaulted if s.default.is_empty() => {
            errs.push(format!("{here}: defaulted without a default"))
        }
        Status::Required | Status::Optional | Status::Hidden if !s.default.is_empty() => errs.push(
            format!("{here}: default given but status is {:?}", s.status),
        ),
        _ => {}
    }
    if let Some(max) = s.max {
        if s.min > max || max == 0 {
            errs.push(format!("{here}: bad value count {}..{max}", s.min));
        }
    }
    if let Some(into) = &s.into {
        if into.is_empty() {
            errs.push(format!("{here}: empty into list"));
        }
        for l in into {
            if !lit_fits(l, &s.ty) {
                errs.push(format!("{here}: into value {l:?} does not fit {:?}", s.ty));
            }
        }
    }
    if !s.default.is_empty() {
        let n = s.default.len();
        if n < s.min || s.max.is_some_and(|m| n > m) {
            errs.push(format!("{here}: {n} default values outside the count"));
        }
    }
    for l in &s.default {
        if !lit_fits(l, &s.ty) {
            errs.push(format!("{here}: default {l:?} does not fit {:?}", s.ty));
        }
        if let Some(into) = &s.into {
            if !into.contains(l) {
                errs.push(format!("{here}: default {l:?} not in its into list"));
            }
        }
        if let Some(v) = lit_value(l) {
            if s.val_min.is_some_and(|m| v < m) || s.val_max.is_some_and(|m| v > m) {
                errs.push(format!("{here}: default {v} outside its bounds"));
            }
        }
    }
    if let (Some(a), Some(b)) = (s.val_min, s.val_max) {
        if a > b {
            errs.push(format!("{here}: val_min > val_max"));
        }
    }
}

/// Checks one level (command or factor occurrence) and recurses.
fn check_level(kws: &[Keyword], rules: &[Rule], path: &str, errs: &mut Vec<String>) {
    let mut ds = Vec::new();
    decls(kws, &[], &mut ds);
    let mut bs = Vec::new();
    blocks(kws, &mut bs);
    let names: BTreeSet<&str> = ds.iter().map(|d| d.kw.name()).collect();

    let all_rules: Vec<&Rule> = rules
        .iter()
        .chain(bs.iter().flat_map(|b| &b.rules))
        .collect();
    for r in &all_rules {
        for n in rule_names(r) {
            if !names.contains(n) {
                errs.push(format!("{path}: rule names unknown keyword {n}"));
            }
        }
    }
    for b in &bs {
        let mut cn = Vec::new();
        cond_names(&b.condition, &mut cn);
        for n in cn {
            if !names.contains(n) {
                errs.push(format!(
                    "{path}: block {} tests unknown keyword {n}",
                    b.name
                ));
            }
        }
        check_cond_values(&b.condition, &ds, path, b.name, errs);
    }

    let groups: Vec<Vec<&'static str>> = rules
        .iter()
        .filter_map(|r| match r {
            Rule::ExactlyOne(k) | Rule::Exclusive(k) => Some(k.clone()),
            _ => None,
        })
        .collect();
    for (i, a) in ds.iter().enumerate() {
        for b in &ds[i + 1..] {
            if a.kw.name() == b.kw.name() && !exclusive(a, b, &groups) {
                errs.push(format!(
                    "{path}: {} declared twice where both can be active",
                    a.kw.name()
                ));
            }
        }
    }

    for d in &ds {
        match d.kw {
            Keyword::Simple(s) => check_simple(s, path, errs),
            Keyword::Factor(f) => {
                if f.max.is_some_and(|m| m < f.min.max(1)) {
                    errs.push(format!("{path}/{}: bad occurrence count", f.name));
                }
                check_level(&f.keywords, &f.rules, &format!("{path}/{}", f.name), errs)
            }
            Keyword::Block(_) => unreachable!("decls looks through blocks"),
        }
    }
}

/// A value tested by a block condition must be one the keyword can take:
/// catches a condition that can never hold because of a typo.
fn check_cond_values(c: &Cond, ds: &[Decl], path: &str, block: &str, errs: &mut Vec<String>) {
    let mut pairs: Vec<(&str, &Lit)> = Vec::new();
    fn collect<'a>(c: &'a Cond, out: &mut Vec<(&'static str, &'a Lit)>) {
        match c {
            Cond::Eq(k, v) => out.push((k, v)),
            Cond::In(k, vs) => vs.iter().for_each(|v| out.push((k, v))),
            Cond::And(v) | Cond::Or(v) => v.iter().for_each(|c| collect(c, out)),
            Cond::Not(c) => collect(c, out),
            Cond::Present(_) | Cond::Absent(_) => {}
        }
    }
    collect(c, &mut pairs);
    for (k, v) in pairs {
        let ok = ds.iter().any(|d| match d.kw {
            Keyword::Simple(s) if s.name == k => {
                lit_fits(v, &s.ty) && s.into.as_ref().is_none_or(|into| into.contains(v))
            }
            _ => false,
        });
        if !ok {
            errs.push(format!(
                "{path}: block {block} tests {k} = {v:?}, a value {k} cannot take"
            ));
        }
    }
}

/// Resolves `KEY` or `FACT/KEY` from the top level of a command.
fn find_simple<'a>(kws: &'a [Keyword], path: &str) -> Vec<&'a Simple> {
    let (head, rest) = match path.split_once('/') {
        Some((h, r)) => (h, Some(r)),
        None => (path, None),
    };
    let mut ds = Vec::new();
    decls(kws, &[], &mut ds);
    let mut found = Vec::new();
    for d in ds.iter().filter(|d| d.kw.name() == head) {
        match (d.kw, rest) {
            (Keyword::Simple(s), None) => found.push(s),
            (Keyword::Factor(f), Some(r)) => found.extend(find_simple(&f.keywords, r)),
            _ => {}
        }
    }
    found
}

fn check_command(c: &CommandSpec, errs: &mut Vec<String>) {
    if c.doc.is_empty() {
        errs.push(format!("{}: no doc", c.name));
    }
    check_level(&c.keywords, &c.rules, c.name, errs);
    let key = match &c.reentrant {
        Reentrant::No => None,
        Reentrant::Optional(k) | Reentrant::Required(k) => Some(*k),
    };
    if let Some(k) = key {
        let ty = match &c.produces {
            Produces::Concept(ty) | Produces::SameAs(_, ty) | Produces::ByText(_, _, ty) => ty,
            Produces::Nothing => {
                errs.push(format!("{}: reuse on a procedure", c.name));
                return;
            }
        };
        let found = find_simple(&c.keywords, k);
        let ok = found
            .iter()
            .any(|s| matches!(&s.ty, Ty::Concept(tys) if tys.contains(ty)));
        if !ok {
            errs.push(format!(
                "{}: reused concept {k} is not a keyword of type {ty}",
                c.name
            ));
        }
    }
}

#[test]
fn every_declaration_is_well_formed() {
    let mut errs = Vec::new();
    for d in commands::all() {
        check_command(&d.spec, &mut errs);
    }
    assert!(
        errs.is_empty(),
        "ill-formed catalogue:\n{}",
        errs.join("\n")
    );
}

/// The well-formedness check itself must catch each kind of mistake.
#[test]
fn well_formedness_check_catches_mistakes() {
    let bad = command(
        "BAD",
        Produces::Concept(aster::concepts::ConceptType::Table),
        vec![
            text("SCHEMA")
                .into(&["A", "B"])
                .default(Lit::Text("A"))
                .kw(),
            real("X").kw(),
            // Both blocks can hold at once (A and Present(X)): duplicate.
            block(
                "b1",
                Cond::Eq("SCHEMA", Lit::Text("A")),
                vec![real("P").default(Lit::Real(1.0)).kw()],
            )
            .kw(),
            block("b2", Cond::Present("X"), vec![real("P").required().kw()]).kw(),
            // Exclusive by value: fine.
            block(
                "b3",
                Cond::Eq("SCHEMA", Lit::Text("B")),
                vec![real("Q").kw()],
            )
            .kw(),
            block(
                "b4",
                Cond::Not(Box::new(Cond::Eq("SCHEMA", Lit::Text("B")))),
                vec![real("Q").kw()],
            )
            .kw(),
            // A value SCHEMA cannot take; an unknown name.
            block("b5", Cond::Eq("SCHEMA", Lit::Text("C")), vec![]).kw(),
            block("b6", Cond::Present("NOPE"), vec![]).kw(),
            // Default outside the into list and bounds; defaulted without default.
            int("N").into_ints(&[1, 2]).default(Lit::Int(3)).kw(),
            real("R").min_val(0.0).default(Lit::Real(-1.0)).kw(),
            Keyword::Simple(Simple {
                status: Status::Defaulted,
                ..real("D")
            }),
        ],
    )
    .doc("test")
    .reentrant(Reentrant::Required("MAILLAGE"))
    .rules(vec![un_parmi(&["X", "MISSING"])]);
    let mut errs = Vec::new();
    check_command(&bad, &mut errs);
    let has = |s: &str| errs.iter().any(|e| e.contains(s));
    assert!(has("P declared twice"), "{errs:#?}");
    assert!(!has("Q declared twice"), "{errs:#?}");
    assert!(has("cannot take"), "{errs:#?}");
    assert!(has("unknown keyword NOPE"), "{errs:#?}");
    assert!(has("unknown keyword MISSING"), "{errs:#?}");
    assert!(
        has("BAD/N: default Int(3) not in its into list"),
        "{errs:#?}"
    );
    assert!(has("BAD/R: default -1 outside its bounds"), "{errs:#?}");
    assert!(has("BAD/D: defaulted without a default"), "{errs:#?}");
    assert!(has("reused concept MAILLAGE"), "{errs:#?}");
    assert_eq!(errs.len(), 8, "{errs:#?}");
}

// ---------------------------------------------------------------------------
// Facts of semantics.md and sdnv103.md carried by the declarations.

/// Every declaration of `path` (`CMD/FACT/KEY`) with its enclosing block
/// conditions at its own level.
fn lookup(path: &str) -> Vec<(Simple, Vec<Cond>)> {
    let mut parts = path.split('/');
    let cmd = commands::find(parts.next().unwrap()).expect("command");
    let rest: Vec<&str> = parts.collect();
    let mut found = Vec::new();
    fn walk(kws: &[Keyword], rest: &[&str], out: &mut Vec<(Simple, Vec<Cond>)>) {
        let mut ds = Vec::new();
        decls(kws, &[], &mut ds);
        for d in ds.iter().filter(|d| d.kw.name() == rest[0]) {
            match d.kw {
                Keyword::Simple(s) if rest.len() == 1 => {
                    out.push((s.clone(), d.conds.iter().map(|c| (*c).clone()).collect()))
                }
                Keyword::Factor(f) if rest.len() > 1 => walk(&f.keywords, &rest[1..], out),
                _ => {}
            }
        }
    }
    walk(&cmd.spec.keywords, &rest, &mut found);
    found
}

#[test]
fn keywords_of_sdnv103_section_4_are_declared() {
    let paths = [
        "LIRE_MAILLAGE/FORMAT",
        "LIRE_MAILLAGE/UNITE",
        "DEFI_GROUP/MAILLAGE",
        "DEFI_GROUP/CREA_GROUP_NO/TOUT_GROUP_MA",
        "DEFI_GROUP/CREA_GROUP_NO/GROUP_MA",
        "DEFI_GROUP/CREA_GROUP_NO/NOM",
        "DEFI_GROUP/CREA_GROUP_NO/CRIT_NOEUD",
        "DEFI_GROUP/CREA_GROUP_NO/DIFFE",
        "DEFI_GROUP/CREA_GROUP_NO/OPTION",
        "DEFI_GROUP/CREA_GROUP_NO/POINT",
        "DEFI_GROUP/CREA_GROUP_NO/VECT_NORMALE",
        "DEFI_GROUP/CREA_GROUP_NO/PRECISION",
        "MODI_MAILLAGE/ORIE_PEAU_2D/GROUP_MA",
        "MODI_MAILLAGE/ORIE_PEAU_3D/GROUP_MA",
        "MODI_MAILLAGE/INFO",
        "CREA_MAILLAGE/MAILLAGE",
        "CREA_MAILLAGE/QUAD_LINE/TOUT",
        "AFFE_MODELE/AFFE/TOUT",
        "AFFE_MODELE/AFFE/GROUP_MA",
        "AFFE_MODELE/AFFE/PHENOMENE",
        "AFFE_MODELE/AFFE/MODELISATION",
        "DEFI_MATERIAU/ELAS/E",
        "DEFI_MATERIAU/ELAS/NU",
        "DEFI_MATERIAU/ELAS/RHO",
        "DEFI_MATERIAU/ECRO_LINE/D_SIGM_EPSI",
        "DEFI_MATERIAU/ECRO_LINE/SY",
        "DEFI_MATERIAU/ECRO_COOK/A",
        "DEFI_MATERIAU/ECRO_COOK/B",
        "DEFI_MATERIAU/ECRO_COOK/C",
        "DEFI_MATERIAU/ECRO_COOK/N_PUIS",
        "DEFI_MATERIAU/ECRO_COOK/M_PUIS",
        "DEFI_MATERIAU/ECRO_COOK/EPSP0",
        "DEFI_MATERIAU/ECRO_COOK/TROOM",
        "DEFI_MATERIAU/ECRO_COOK/TMELT",
        "AFFE_MATERIAU/MAILLAGE",
        "AFFE_MATERIAU/AFFE/MATER",
        "AFFE_CHAR_MECA/MODELE",
        "AFFE_CHAR_MECA/DDL_IMPO/GROUP_NO",
        "AFFE_CHAR_MECA/DDL_IMPO/DZ",
        "AFFE_CHAR_MECA/INFO",
        "DEFI_CONTACT/FORMULATION",
        "DEFI_CONTACT/REAC_GEOM",
        "DEFI_CONTACT/NB_ITER_GEOM",
        "DEFI_CONTACT/FROTTEMENT",
        "DEFI_CONTACT/ALGO_RESO_CONT",
        "DEFI_CONTACT/ALGO_RESO_GEOM",
        "DEFI_CONTACT/ALGO_RESO_FROT",
        "DEFI_CONTACT/ZONE/ALGO_CONT",
        "DEFI_CONTACT/ZONE/ALGO_FROT",
        "DEFI_CONTACT/ZONE/COULOMB",
        "DEFI_CONTACT/ZONE/E_N",
        "DEFI_CONTACT/ZONE/E_T",
        "DEFI_CONTACT/ZONE/COEF_MATR_FROT",
        "DEFI_CONTACT/ZONE/APPARIEMENT",
        "DEFI_CONTACT/ZONE/GROUP_MA_MAIT",
        "DEFI_CONTACT/ZONE/GROUP_MA_ESCL",
        "DEFI_CONTACT/ZONE/GROUP_NO",
        "DEFI_CONTACT/ZONE/NOM_CMP",
        "DEFI_CONTACT/ZONE/COEF_IMPO",
        "DEFI_CONTACT/ZONE/COEF_MULT",
        "DEFI_CONTACT/ZONE/COEF_PENA",
        "DEFI_CONSTANTE/VALE",
        "CREA_CHAMP/TYPE_CHAM",
        "CREA_CHAMP/OPERATION",
        "CREA_CHAMP/MODELE",
        "CREA_CHAMP/AFFE/GROUP_NO",
        "CREA_CHAMP/AFFE/NOM_CMP",
        "CREA_CHAMP/AFFE/VALE",
        "DEFI_LIST_REEL/DEBUT",
        "DEFI_LIST_REEL/INTERVALLE/JUSQU_A",
        "DEFI_LIST_REEL/INTERVALLE/NOMBRE",
        "DEFI_LIST_INST/METHODE",
        "DEFI_LIST_INST/DEFI_LIST/LIST_INST",
        "DEFI_LIST_INST/ECHEC/EVENEMENT",
        "DEFI_LIST_INST/ECHEC/ACTION",
        "DEFI_LIST_INST/ECHEC/SUBD_METHODE",
        "DEFI_LIST_INST/ECHEC/SUBD_PAS",
        "DEFI_LIST_INST/ECHEC/SUBD_PAS_MINI",
        "DEFI_LIST_INST/ECHEC/SUBD_INST",
        "DEFI_LIST_INST/ECHEC/SUBD_DUREE",
        "DEFI_LIST_INST/ECHEC/PENE_MAXI",
        "DEFI_LIST_INST/ECHEC/COEF_MAXI",
        "DEFI_LIST_INST/INFO",
        "DYNA_NON_LINE/MODELE",
        "DYNA_NON_LINE/CHAM_MATER",
        "DYNA_NON_LINE/EXCIT/CHARGE",
        "DYNA_NON_LINE/CONTACT",
        "DYNA_NON_LINE/COMPORTEMENT/RELATION",
        "DYNA_NON_LINE/COMPORTEMENT/DEFORMATION",
        "DYNA_NON_LINE/COMPORTEMENT/ALGO_INTE",
        "DYNA_NON_LINE/COMPORTEMENT/ITER_INTE_MAXI",
        "DYNA_NON_LINE/COMPORTEMENT/TOUT",
        "DYNA_NON_LINE/COMPORTEMENT/GROUP_MA",
        "DYNA_NON_LINE/ETAT_INIT/VITE",
        "DYNA_NON_LINE/ETAT_INIT/EVOL_NOLI",
        "DYNA_NON_LINE/INCREMENT/LIST_INST",
        "DYNA_NON_LINE/INCREMENT/INST_INIT",
        "DYNA_NON_LINE/INCREMENT/INST_FIN",
        "DYNA_NON_LINE/SCHEMA_TEMPS/SCHEMA",
        "DYNA_NON_LINE/SCHEMA_TEMPS/FORMULATION",
        "DYNA_NON_LINE/SCHEMA_TEMPS/BETA",
        "DYNA_NON_LINE/SCHEMA_TEMPS/GAMMA",
        "DYNA_NON_LINE/SCHEMA_TEMPS/ALPHA",
        "DYNA_NON_LINE/SCHEMA_TEMPS/MODI_EQUI",
        "DYNA_NON_LINE/NEWTON/MATRICE",
        "DYNA_NON_LINE/NEWTON/REAC_INCR",
        "DYNA_NON_LINE/NEWTON/REAC_ITER",
        "DYNA_NON_LINE/NEWTON/MATR_RIGI_SYME",
        "DYNA_NON_LINE/CONVERGENCE/RESI_GLOB_RELA",
        "DYNA_NON_LINE/CONVERGENCE/RESI_GLOB_MAXI",
        "DYNA_NON_LINE/CONVERGENCE/ITER_GLOB_MAXI",
        "DYNA_NON_LINE/CONVERGENCE/ARRET",
        "DYNA_NON_LINE/SOLVEUR/METHODE",
        "DYNA_NON_LINE/SOLVEUR/POSTTRAITEMENTS",
        "DYNA_NON_LINE/ARCHIVAGE/LIST_INST",
        "DYNA_NON_LINE/SUIVI_DDL/NOM_CMP",
        "DYNA_NON_LINE/SUIVI_DDL/NOM_CHAM",
        "DYNA_NON_LINE/SUIVI_DDL/TOUT",
        "DYNA_NON_LINE/SUIVI_DDL/EVAL_ELGA",
        "DYNA_NON_LINE/SUIVI_DDL/EVAL_CHAM",
        "CALC_CHAMP/RESULTAT",
        "CALC_CHAMP/FORCE",
        "POST_RELEVE_T/ACTION/INTITULE",
        "POST_RELEVE_T/ACTION/GROUP_NO",
        "POST_RELEVE_T/ACTION/RESULTAT",
        "POST_RELEVE_T/ACTION/NOM_CHAM",
        "POST_RELEVE_T/ACTION/NOM_CMP",
        "POST_RELEVE_T/ACTION/TOUT_CMP",
        "POST_RELEVE_T/ACTION/OPERATION",
        "TEST_RESU/RESU/GROUP_NO",
        "TEST_RESU/RESU/INST",
        "TEST_RESU/RESU/NUME_ORDRE",
        "TEST_RESU/RESU/RESULTAT",
        "TEST_RESU/RESU/NOM_CHAM",
        "TEST_RESU/RESU/NOM_CMP",
        "TEST_RESU/RESU/VALE_CALC",
        "TEST_RESU/RESU/VALE_REFE",
        "TEST_RESU/RESU/REFERENCE",
        "TEST_RESU/RESU/CRITERE",
        "TEST_RESU/RESU/PRECISION",
        "TEST_RESU/RESU/TOLE_MACHINE",
        "TEST_TABLE/TABLE",
        "TEST_TABLE/NOM_PARA",
        "TEST_TABLE/VALE_CALC",
        "TEST_TABLE/CRITERE",
        "TEST_TABLE/FILTRE/NOM_PARA",
        "TEST_TABLE/FILTRE/VALE",
        "TEST_TABLE/FILTRE/VALE_I",
        "TEST_TABLE/FILTRE/PRECISION",
        "TEST_TABLE/FILTRE/CRIT_COMP",
        "IMPR_TABLE/TABLE",
        "IMPR_TABLE/FORMAT",
        "IMPR_TABLE/UNITE",
        "IMPR_TABLE/NOM_PARA",
        "IMPR_TABLE/TITRE",
        "IMPR_RESU/FORMAT",
        "IMPR_RESU/RESU/RESULTAT",
        "RECU_FONCTION/RESULTAT",
        "RECU_FONCTION/NOM_CHAM",
        "RECU_FONCTION/GROUP_NO",
        "RECU_FONCTION/NOM_CMP",
        "IMPR_FONCTION/FORMAT",
        "IMPR_FONCTION/UNITE",
        "IMPR_FONCTION/COURBE/FONCTION",
    ];
    let missing: Vec<&str> = paths
        .iter()
        .copied()
        .filter(|p| lookup(p).is_empty())
        .collect();
    assert!(missing.is_empty(), "not declared: {missing:?}");
}

fn only_default(path: &str) -> (Lit, Vec<Cond>) {
    let found = lookup(path);
    assert_eq!(found.len(), 1, "{path} should be declared once");
    let (s, conds) = found.into_iter().next().unwrap();
    assert_eq!(s.status, Status::Defaulted, "{path}");
    (s.default[0].clone(), conds)
}

fn text_cond(c: &[Cond]) -> String {
    c.iter()
        .map(aster::catalog::doc::cond_text)
        .collect::<Vec<_>>()
        .join(" & ")
}

/// Defaults and their conditions from semantics.md section 8.1.
#[test]
fn schema_temps_defaults_follow_code_aster() {
    let cases = [
        ("BETA", Lit::Real(0.25), "`SCHEMA` = 'NEWMARK'"),
        ("GAMMA", Lit::Real(0.5), "`SCHEMA` = 'NEWMARK'"),
        ("ALPHA", Lit::Real(-0.1), "`SCHEMA` = 'HHT'"),
        ("MODI_EQUI", Lit::Text("OUI"), "`SCHEMA` = 'HHT'"),
    ];
    for (k, v, cond) in cases {
        let (d, c) = only_default(&format!("DYNA_NON_LINE/SCHEMA_TEMPS/{k}"));
        assert_eq!(d, v, "{k}");
        assert_eq!(text_cond(&c), cond, "{k}");
    }
}

/// semantics.md 6.3: discrete zones take E_N only under penalised contact
/// and E_T, COULOMB only with Coulomb friction.
#[test]
fn discrete_contact_zone_blocks() {
    let e_n = lookup("DEFI_CONTACT/ZONE/E_N");
    assert_eq!(e_n.len(), 2, "E_N in both discrete zones");
    for (s, c) in &e_n {
        assert_eq!(s.status, Status::Required);
        assert_eq!(text_cond(c), "`ALGO_CONT` = 'PENALISATION'");
    }
    let e_t = lookup("DEFI_CONTACT/ZONE/E_T");
    assert_eq!(e_t.len(), 1, "E_T only in the discrete zone with friction");
    let coulomb = lookup("DEFI_CONTACT/ZONE/COULOMB");
    assert_eq!(
        coulomb.len(),
        2,
        "COULOMB in the discrete and continuous friction zones"
    );
    let (d, _) = lookup("DEFI_CONTACT/ZONE/COEF_MATR_FROT")
        .into_iter()
        .next()
        .unwrap();
    assert_eq!(d.default, vec![Lit::Real(0.0)]);
}

/// The deliberate deviation: VALE_CALC is optional in aster.
#[test]
fn vale_calc_is_optional() {
    for p in ["TEST_RESU/RESU/VALE_CALC", "TEST_TABLE/VALE_CALC"] {
        let found = lookup(p);
        assert_eq!(found.len(), 1);
        assert_eq!(found[0].0.status, Status::Optional, "{p}");
    }
}

#[test]
fn reentrant_flags() {
    let flag = |n: &str| commands::find(n).unwrap().spec.reentrant;
    assert_eq!(flag("DEFI_GROUP"), Reentrant::Required("MAILLAGE"));
    assert_eq!(flag("MODI_MAILLAGE"), Reentrant::Required("MAILLAGE"));
    assert_eq!(flag("CALC_CHAMP"), Reentrant::Optional("RESULTAT"));
    assert_eq!(
        flag("DYNA_NON_LINE"),
        Reentrant::Optional("ETAT_INIT/EVOL_NOLI")
    );
    for n in [
        "CREA_MAILLAGE",
        "LIRE_MAILLAGE",
        "AFFE_MODELE",
        "DEFI_CONTACT",
        "DEFI_LIST_INST",
        "POST_RELEVE_T",
        "RECU_FONCTION",
    ] {
        assert_eq!(flag(n), Reentrant::No, "{n}");
    }
}
