//! The Python idioms of code_aster 16+ command files (docs/language.md):
//! DEBUT(CODE='OUI', ERREUR=_F(ALARME='EXCEPTION')), dicts of keywords
//! passed with `**`, item assignment, and print() to the .mess. A study
//! written with them runs exactly as the same study written flat, and each
//! misuse is a located error.

use aster::catalog::checker::{check_program, CheckedProgram};
use aster::commands;
use aster::diag::{Diagnostic, Source};
use aster::lang::parser::parse;
use aster::run::driver::{run_file, RunOptions};

mod common;

fn check(text: &str) -> Result<CheckedProgram, Vec<Diagnostic>> {
    let src = Source::new("t.comm", text);
    let p = parse(&src).map_err(|d| vec![d])?;
    check_program(&p, &commands::all())
}

/// The start of a study whose names the snippets use: MO, CHMAT, L_INST.
const HEAD: &str = "\
DEBUT()
MAIL = LIRE_MAILLAGE(FORMAT='MED')
MO = AFFE_MODELE(MAILLAGE=MAIL, AFFE=_F(GROUP_MA='VOL', PHENOMENE='MECANIQUE', MODELISATION='AXIS'))
MAT = DEFI_MATERIAU(ELAS=_F(E=117.E3, NU=0.35, RHO=8.93E-9))
CHMAT = AFFE_MATERIAU(MAILLAGE=MAIL, AFFE=_F(GROUP_MA='VOL', MATER=MAT))
L_INST = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1.E-5, NOMBRE=2))
";

/// The errors of `HEAD + text + FIN()`, each with its message, notes and
/// line and column (lines counted from the first line of `text`).
fn errors(text: &str) -> Vec<(String, Vec<String>, usize, usize)> {
    let full = format!("{HEAD}{text}\nFIN()\n");
    let ds = check(&full).expect_err(text);
    let src = Source::new("t.comm", full.as_str());
    let head_lines = HEAD.lines().count();
    ds.iter()
        .filter(|d| d.severity == aster::diag::Severity::Error)
        .map(|d| {
            let (l, c) = src.line_col(d.span.expect("located").start);
            (d.message.clone(), d.notes.clone(), l - head_lines, c)
        })
        .collect()
}

fn first_error(text: &str) -> (String, usize, usize) {
    let (m, _, l, c) = errors(text).swap_remove(0);
    (m, l, c)
}

#[test]
fn dict_study_runs_as_its_flat_version() {
    let py = common::run_study(
        "tests/verification/python_dicts_free_flight.comm",
        "py_dicts",
    );
    let flat = common::run_study(
        "tests/verification/python_free_flight_flat.comm",
        "py_dicts_flat",
    );
    assert_eq!(py.code, 0, "{}", py.term);
    assert_eq!(flat.code, 0, "{}", flat.term);
    let a = py.file("python_dicts_free_flight.resu");
    // 11 analytic references (rigid-body motion, to 1e-10 relative), the
    // same .resu byte for byte as the flat file's.
    let ok = a.lines().filter(|l| l.starts_with(" OK ")).count();
    assert_eq!(ok, 11, "{a}");
    assert!(!a.lines().any(|l| l.starts_with("NOOK")), "{a}");
    assert_eq!(a, flat.file("python_free_flight_flat.resu"));
    // The same commands in the same order.
    let names = |f: &str| -> Vec<String> {
        let src = Source::read(std::path::Path::new(&format!(
            "{}/tests/verification/{f}.comm",
            env!("CARGO_MANIFEST_DIR")
        )))
        .unwrap();
        let c = check_program(&parse(&src).unwrap(), &commands::all()).unwrap();
        c.commands.iter().map(|c| c.name.clone()).collect()
    };
    assert_eq!(
        names("python_dicts_free_flight"),
        names("python_free_flight_flat")
    );
    // print() writes Python's text, in its place among the commands.
    let mess = py.file("python_dicts_free_flight.mess");
    let at = |needle: &str| {
        mess.find(needle)
            .unwrap_or_else(|| panic!("{needle:?} not in the .mess:\n{mess}"))
    };
    let shared = at("\nNPAS = 10 keywords shared: 5\n");
    assert!(at("# ---- VITINI = CREA_CHAMP") < shared);
    assert!(shared < at("# ---- RES = DYNA_NON_LINE"));
    // str(V0 * t) as Python writes it: -227000. * 5e-06 and * 1e-05.
    let s5 = at("\nstep 5 DY = -1.135\n");
    let s10 = at("\nstep 10 DY = -2.27\n");
    assert!(s5 < s10);
    assert!(at("\ndone: VITE checked at ['A2', 'B1']\n") < at("# ---- FIN"));
}

#[test]
fn dicts_and_item_assignment_have_python_values() {
    let text = format!(
        "{HEAD}\
d = {{'A': 1, 'B': 2, 'A': 3}}
e = dict(d, B=5, C=6)
f = _F(**e)
f['D'] = [None] * 2
g = list(f['D'])
g[1] = len(f)
L = DEFI_LIST_REEL(VALE=(d['A'], e['B'], e['C'], g[1], len(d)))
FIN()
"
    );
    let c = check(&text).unwrap_or_else(|ds| panic!("{}", ds[0].message));
    // CPython 3: {'A': 3, 'B': 2}, then B=5, C=6; len(f) is 4 with D.
    assert_eq!(c.commands.last().map(|c| c.name.as_str()), Some("FIN"));
    let l = &c.commands[c.commands.len() - 2];
    assert_eq!(l.args.reals("VALE"), vec![3.0, 5.0, 6.0, 4.0, 2.0]);
}

/// Augmented assignment of a name: numbers, texts and tuples as
/// `A = A op x`, a list extended in place by `+=` (any iterable, as
/// list.extend) and repeated by `*=`; values as CPython 3 gives them.
#[test]
fn augmented_assignment_has_python_values() {
    let text = format!(
        "{HEAD}\
N = 7
N += 2
N -= 1
N *= 3
N //= 5
X = 7.
X /= 2
X **= 2
X %= 5
S = 'DEPL'
S += '_A1'
T = (1,)
T += (2,)
L = [1.]
L += (2., 3.)
L += [N]
L *= 2
for k in range(3):
    N += k
A = DEFI_LIST_REEL(VALE=L)
B = DEFI_LIST_REEL(VALE=(N, X, len(S), len(T)))
FIN()
"
    );
    let c = check(&text).unwrap_or_else(|ds| panic!("{}", ds[0].message));
    // CPython 3: N = ((7 + 2 - 1) * 3) // 5 = 4, then + 0 + 1 + 2 = 7;
    // X = (3.5 ** 2) % 5 = 2.25; S = 'DEPL_A1'; T = (1, 2);
    // L = [1., 2., 3., 4] * 2.
    let n = c.commands.len();
    assert_eq!(
        c.commands[n - 3].args.reals("VALE"),
        vec![1.0, 2.0, 3.0, 4.0, 1.0, 2.0, 3.0, 4.0]
    );
    assert_eq!(
        c.commands[n - 2].args.reals("VALE"),
        vec![7.0, 2.25, 7.0, 2.0]
    );
}

/// What Python's in-place `+=` on a list would do differently from
/// aster's copies is refused, located.
#[test]
fn augmented_assignment_mistakes_are_located() {
    for (text, msg, line, col) in [
        (
            "L = [1]\nM = L\nL += [2]",
            "L is the same list as M: Python's += would change both",
            3,
            1,
        ),
        ("L = [1]\nM = [L]\nL *= 2", "L is the same list as M", 3, 1),
        (
            "L = [1]\nfor x in L:\n    L += [2]",
            "while it is being looped over",
            3,
            5,
        ),
        ("L = [1]\nL += 2", "cannot loop over the integer 2", 2, 6),
        ("T = (1,)\nT += [2]", "tuple", 2, 1),
        ("Z += 1", "name 'Z' is not defined", 1, 1),
        (
            "S = 'A'\nS -= 'B'",
            "operator '-' cannot combine the text 'A' and the text 'B'",
            2,
            1,
        ),
    ] {
        let (m, l, c) = first_error(text);
        assert!(m.contains(msg), "{text:?}: {m}");
        assert_eq!((l, c), (line, col), "{text:?}: {m}");
    }
}

#[test]
fn keywords_from_a_dict_are_checked_against_the_catalogue() {
    let run = "\
common = dict(MODELE=MO, CHAM_MATER=CHMAT)
RES = DYNA_NON_LINE(**common, INCREMENT=_F(LIST_INST=L_INST),
                    COMPORTEMENT=_F(RELATION='ELAS'),
                    SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'))
RES2 = DYNA_NON_LINE(INCREMENT=_F(LIST_INST=L_INST), **common,
                     COMPORTEMENT=_F(RELATION='ELAS'),
                     SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'))
";
    let c = check(&format!("{HEAD}{run}FIN()\n")).unwrap_or_else(|ds| panic!("{ds:?}"));
    let dnl: Vec<_> = c
        .commands
        .iter()
        .filter(|c| c.name == "DYNA_NON_LINE")
        .collect();
    assert_eq!(dnl.len(), 2);
    for d in dnl {
        assert_eq!(d.args.concept("MODELE"), Some("MO"));
        assert_eq!(d.args.concept("CHAM_MATER"), Some("CHMAT"));
    }
    // A misspelt keyword in the dict: at the dict's entry, with a note
    // naming the **.
    let bad = run.replace("dict(MODELE=MO", "dict(MODELLE=MO");
    let errs = errors(&bad);
    let (m, notes, l, c) = &errs[0];
    assert_eq!(
        (m.as_str(), *l, *c),
        ("unknown keyword MODELLE for DYNA_NON_LINE", 1, 15),
        "{errs:?}"
    );
    assert!(notes.iter().any(|n| n.contains("** unpacks")), "{notes:?}");
    // A wrong value type in the dict, at the value.
    let bad = run.replace("dict(MODELE=MO", "dict(MODELE=CHMAT");
    let (m, l, c) = first_error(&bad);
    assert!(m.contains("CHMAT is a"), "{m}");
    assert_eq!((l, c), (1, 22));
    // A keyword given twice: Python's TypeError, at the second one.
    let (m, l, c) = first_error(&run.replace(
        "RES = DYNA_NON_LINE(**common,",
        "RES = DYNA_NON_LINE(**common, MODELE=MO,",
    ));
    assert_eq!((m.as_str(), l, c), ("keyword MODELE is given twice", 2, 31));
    let errs = errors(&run.replace(
        "RES2 = DYNA_NON_LINE(INCREMENT=_F(LIST_INST=L_INST),",
        "RES2 = DYNA_NON_LINE(MODELE=MO, INCREMENT=_F(LIST_INST=L_INST),",
    ));
    let (m, notes, l, c) = &errs[0];
    assert_eq!(
        (m.as_str(), *l, *c),
        ("keyword MODELE is given twice", 5, 65)
    );
    assert!(
        notes.iter().any(|n| n.contains("holds MODELE")),
        "{notes:?}"
    );
    // ** of something that is not a dict, or of a concept.
    let (m, l, c) = first_error("RES = DYNA_NON_LINE(**(1, 2))");
    assert!(m.contains("must be a dict"), "{m}");
    assert_eq!((l, c), (1, 23));
    let (m, _, _) = first_error("RES = DYNA_NON_LINE(**MO)");
    assert!(m.contains("'**' unpacks the concept MO"), "{m}");
    // In _F too, and a keyword twice there.
    let (m, l, c) = first_error("kw = {'RELATION': 'ELAS'}\nC = _F(**kw, RELATION='ELAS')");
    assert_eq!(
        (m.as_str(), l, c),
        ("keyword RELATION is repeated in _F(...)", 2, 14)
    );
    let (m, l, c) = first_error("kw = {'RELATION': 'ELAS'}\nC = _F(RELATION='ELAS', **kw)");
    assert_eq!(
        (m.as_str(), l, c),
        ("keyword RELATION is repeated in _F(...)", 2, 25)
    );
}

#[test]
fn item_assignment_and_dict_mistakes_are_located() {
    for (text, msg, line, col) in [
        (
            "L = [1]\nL[1] = 2",
            "list assignment index 1 out of range",
            2,
            3,
        ),
        (
            "T = (1, 2)\nT[0] = 2",
            "does not support item assignment",
            2,
            1,
        ),
        (
            "L = [1]\nM = L\nL[0] = 2",
            "L is the same object as M",
            3,
            1,
        ),
        (
            "D = {}\nE = [D]\nD['A'] = 2",
            "D is the same object as E",
            3,
            1,
        ),
        (
            "D = {'L': [1]}\nL = D['L']\nL[0] = 2",
            "L is the same object as D",
            3,
            1,
        ),
        (
            "L = [1, 2]\nfor x in L:\n    L[1] = 3",
            "while it is being looped over",
            3,
            5,
        ),
        (
            "L = [None]\nL[0] = DEFI_LIST_REEL(VALE=(0., 1.))",
            "cannot be stored in an item of L",
            2,
            8,
        ),
        ("D = {}\nD[1] = 2", "a dict key must be a text", 2, 3),
        ("D = {1: 2}", "a dict key must be a text", 1, 6),
        ("D = {'A': 1}\nX = D['B']", "has no key 'B'", 2, 7),
        (
            "MO['A'] = 1",
            "item assignment changes the concept MO",
            1,
            1,
        ),
        ("Z['A'] = 1", "name 'Z' is not defined", 1, 1),
        ("X = dict(1, 2)", "at most 1 positional argument", 1, 13),
        ("X = dict(3)", "cannot loop over the integer 3", 1, 10),
    ] {
        let (m, l, c) = first_error(text);
        assert!(m.contains(msg), "{text:?}: {m}");
        assert_eq!((l, c), (line, col), "{text:?}: {m}");
    }
}

#[test]
fn print_writes_python_text_and_refuses_what_the_run_knows() {
    let c = check(&format!(
        "{HEAD}print('a', 1, 2.5, [1e-5, None], (True,), {{'K': 'v'}})\nprint('x', 'y', sep='-', end='!')\nprint()\nFIN()\n"
    ))
    .unwrap_or_else(|ds| panic!("{ds:?}"));
    // CPython 3 prints exactly these texts.
    let texts: Vec<&str> = c.prints.iter().map(|(_, t)| t.as_str()).collect();
    assert_eq!(
        texts,
        vec!["a 1 2.5 [1e-05, None] (True,) {'K': 'v'}\n", "x-y!", "\n"]
    );
    // Before FIN, after the last command of HEAD.
    let fin = c.commands.iter().position(|c| c.name == "FIN").unwrap();
    assert!(c.prints.iter().all(|(at, _)| *at == fin));
    for (text, msg, line, col) in [
        (
            "print('R', MO)",
            "print() writes the concept MO, whose content is not known before the study runs",
            1,
            12,
        ),
        ("X = print(1)", "call it as a statement of its own", 1, 5),
        (
            "print(1, file=2)",
            "print() keyword file is not supported",
            1,
            10,
        ),
        ("print(1, sep=2)", "sep must be None or a text", 1, 14),
        ("print(**{'a': 1})", "print(**...) is not supported", 1, 7),
    ] {
        let (m, l, c) = first_error(text);
        assert!(m.contains(msg), "{text:?}: {m}");
        assert_eq!((l, c), (line, col), "{text:?}: {m}");
    }
}

#[test]
fn debut_code_takes_the_text_and_the_older_factor() {
    for ok in [
        "DEBUT(CODE='OUI')",
        "DEBUT(CODE=\"OUI\", ERREUR=_F(ALARME=\"EXCEPTION\"))",
        "DEBUT(CODE='NON', ERREUR=_F(ERREUR_F='EXCEPTION', ALARME='ALARME'))",
        "DEBUT(CODE=_F(NIV_PUB_WEB='INTERNET'))",
        "DEBUT(CODE=_F(NIV_PUB_WEB='INTRANET'), IGNORE_ALARM=('MODELE1_63',))",
    ] {
        let c = check(&format!("{ok}\nFIN()\n")).unwrap_or_else(|ds| panic!("{ok}: {ds:?}"));
        assert_eq!(c.commands[0].args.text("CODE").unwrap_or("OUI"), {
            if ok.contains("NON") {
                "NON"
            } else {
                "OUI"
            }
        });
    }
    for (bad, msg, col) in [
        (
            "DEBUT(CODE='YES')",
            "'YES' is not an allowed value of CODE",
            12,
        ),
        (
            "DEBUT(CODE=_F(NIV_PUB_WEB='WEB'))",
            "CODE/NIV_PUB_WEB takes 'INTERNET' or 'INTRANET'",
            27,
        ),
        (
            "DEBUT(CODE=_F(NIV=1))",
            "unknown keyword NIV in CODE=_F(...)",
            15,
        ),
        ("DEBUT(CODE=_F())", "needs NIV_PUB_WEB", 12),
        (
            "DEBUT(ERREUR=_F(ALARME='ERREUR'))",
            "'ERREUR' is not an allowed value of ALARME",
            24,
        ),
    ] {
        let full = format!("{bad}\nFIN()\n");
        let ds = check(&full).expect_err(bad);
        let src = Source::new("t.comm", full.as_str());
        assert!(ds[0].message.contains(msg), "{bad}: {}", ds[0].message);
        assert_eq!(src.line_col(ds[0].span.unwrap().start), (1, col), "{bad}");
        // NIV is unknown, and NIV_PUB_WEB is missing: both are said.
        let n = if bad.contains("NIV=") { 2 } else { 1 };
        assert_eq!(ds.len(), n, "{bad}: {ds:?}");
    }
}

/// Runs `text` with the mesh of modelling D on unit 20.
fn run_text(tag: &str, text: &str) -> (i32, String, String) {
    let out = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(tag);
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&out).unwrap();
    let comm = out.join("t.comm");
    std::fs::write(&comm, text).unwrap();
    let mut term = Vec::new();
    let code = run_file(
        &RunOptions {
            comm,
            out_dir: Some(out.clone()),
            units: vec![(
                20,
                std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("med/sdnv103d.mmed"),
            )],
            ..RunOptions::default()
        },
        &mut term,
    );
    let mess = std::fs::read_to_string(out.join("t.mess")).unwrap_or_default();
    (code, String::from_utf8(term).unwrap(), mess)
}

#[test]
fn alarme_exception_turns_an_alarm_into_the_error_of_its_command() {
    let study = "\
DEBUT(ERREUR=_F(ALARME='EXCEPTION'))
MAIL = LIRE_MAILLAGE(FORMAT='MED')
MAIL = DEFI_GROUP(reuse=MAIL, MAILLAGE=MAIL, DETR_GROUP_MA=_F(NOM='NOWHERE'))
print('after DEFI_GROUP')
FIN()
";
    let (code, term, mess) = run_text("alarme_exception", study);
    assert_eq!(code, 1, "{term}");
    assert!(
        term.contains(
            "DEFI_GROUP raised an alarm, an error under DEBUT(ERREUR=_F(ALARME='EXCEPTION'))"
        ),
        "{term}"
    );
    assert!(term.contains("t.comm:3:"), "{term}");
    assert!(!mess.contains("after DEFI_GROUP"), "{mess}");
    // Without it, the alarm is printed and the study goes on.
    let (code, term, mess) = run_text(
        "alarme_default",
        &study.replace("DEBUT(ERREUR=_F(ALARME='EXCEPTION'))", "DEBUT(CODE='OUI')"),
    );
    assert_eq!(code, 0, "{term}");
    assert!(
        mess.contains("<A> <DEFI_GROUP> the cell group NOWHERE"),
        "{mess}"
    );
    assert!(mess.contains("\nafter DEFI_GROUP\n"), "{mess}");
}

#[test]
fn code_aster_16_headers_are_accepted_or_refused_where_used() {
    // The header lines of code_aster 16+ test files.
    let c = check(
        "from code_aster.Commands import *\nfrom code_aster import CA\n\nDEBUT(CODE='OUI')\nFIN()\n",
    )
    .unwrap_or_else(|ds| panic!("{ds:?}"));
    assert_eq!(c.commands.len(), 2);
    for (text, msg, note, line, col) in [
        (
            "from code_aster import CA\nCA.init('--test')\nDEBUT()\nFIN()\n",
            "CA.init (code_aster's object interface) is not available",
            "write DEBUT(...) instead",
            2,
            4,
        ),
        (
            "from code_aster import CA\nDEBUT()\ntest = CA.TestCase()\nFIN()\n",
            "CA.TestCase (code_aster's object interface) is not available",
            "use TEST_RESU",
            3,
            11,
        ),
        (
            "from code_aster import MPI\nDEBUT()\nFIN()\n",
            "code_aster.MPI is not available in command files",
            "from code_aster import CA",
            1,
            24,
        ),
        (
            "POURSUITE(CODE='OUI')\nFIN()\n",
            "unknown command POURSUITE",
            "aster does not save",
            1,
            1,
        ),
    ] {
        let ds = check(text).expect_err(text);
        let src = Source::new("t.comm", text);
        assert_eq!(ds.len(), 1, "{text}: {ds:?}");
        assert!(ds[0].message.starts_with(msg), "{text}: {}", ds[0].message);
        assert!(ds[0].notes.iter().any(|n| n.contains(note)), "{ds:?}");
        assert_eq!(
            src.line_col(ds[0].span.unwrap().start),
            (line, col),
            "{text}"
        );
    }
}

#[test]
fn aster_own_limits_are_alarms_that_never_raise() {
    // IMPR_RESU writes VARI_ELGA as cell means (a limit of aster's MED
    // writer, which code_aster does not have): an alarm in the .mess, not
    // an error under ALARME='EXCEPTION', which the study keeps.
    let study = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/verification/python_dicts_free_flight.comm"
    ))
    .unwrap();
    assert!(study.contains("ERREUR=_F(ALARME='EXCEPTION')"));
    let study = study.replace(
        "\nFIN()",
        "\nIMPR_RESU(FORMAT='MED', RESU=_F(RESULTAT=RES, NOM_CHAM=('DEPL', 'VARI_ELGA')))\nFIN()",
    );
    let (code, term, mess) = run_text("alarme_limitation", &study);
    assert_eq!(code, 0, "{term}");
    assert!(
        mess.contains(
            "<A> <IMPR_RESU> RES_____VARI_ELGA: the MED writer cannot store Gauss points yet"
        ),
        "{mess}"
    );
    assert!(mess.contains("# ---- FIN"), "{mess}");
}
