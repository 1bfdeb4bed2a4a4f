//! The Python that study files use around their commands (docs/language.md):
//! a study written with imports, loops, conditions, '%' formatting and
//! comprehensions runs exactly as the same study written flat, and the
//! blocks unroll into the commands Python would run, in order, each
//! located at its own text.

use aster::catalog::args::Args;
use aster::catalog::checker::{check_program, CheckedProgram};
use aster::commands;
use aster::diag::{Diagnostic, Source};
use aster::lang::parser::parse;

mod common;

fn check(text: &str) -> Result<CheckedProgram, Vec<Diagnostic>> {
    let src = Source::new("t.comm", text);
    let p = parse(&src).map_err(|d| vec![d])?;
    check_program(&p, &commands::all())
}

/// The VALE of every DEFI_LIST_REEL of a file, in the order they run.
fn lists(text: &str) -> Vec<Vec<f64>> {
    let c = check(&format!("DEBUT()\n{text}\nFIN()\n")).unwrap_or_else(|ds| {
        let src = Source::new("t.comm", text);
        panic!(
            "{}",
            ds.iter().map(|d| d.render(Some(&src))).collect::<String>()
        )
    });
    c.commands
        .iter()
        .filter(|c| c.name == "DEFI_LIST_REEL")
        .map(|c| c.args.reals("VALE"))
        .collect()
}

/// The first error of a file and its line and column.
fn error(text: &str) -> (String, usize, usize) {
    let full = format!("DEBUT()\n{text}\nFIN()\n");
    let ds = check(&full).expect_err(text);
    let d = &ds[0];
    let src = Source::new("t.comm", full.as_str());
    let (l, c) = src.line_col(d.span.expect("located").start);
    (d.message.clone(), l - 1, c)
}

#[test]
fn python_study_runs_as_its_flat_version() {
    let py = common::run_study("tests/verification/python_free_flight.comm", "py_ff");
    let flat = common::run_study(
        "tests/verification/python_free_flight_flat.comm",
        "py_ff_flat",
    );
    assert_eq!(py.code, 0, "{}", py.term);
    assert_eq!(flat.code, 0, "{}", flat.term);
    let (a, b) = (
        py.file("python_free_flight.resu"),
        flat.file("python_free_flight_flat.resu"),
    );
    // 4 DY checks and the end velocity for both schemes, DX for Newmark:
    // 11 analytic references (rigid-body motion, to 1e-10 relative).
    let ok = a.lines().filter(|l| l.starts_with(" OK ")).count();
    assert_eq!(ok, 11, "{a}");
    assert!(!a.lines().any(|l| l.starts_with("NOOK")), "{a}");
    assert_eq!(a, b, "the two .resu differ");
    // The same commands, in the same order.
    let names = |f: &str| -> Vec<String> {
        let src = Source::read(std::path::Path::new(&format!(
            "{}/tests/verification/{f}.comm",
            env!("CARGO_MANIFEST_DIR")
        )))
        .unwrap();
        let p = parse(&src).unwrap();
        let c = check_program(&p, &commands::all()).unwrap();
        c.commands.iter().map(|c| c.name.clone()).collect()
    };
    assert_eq!(
        names("python_free_flight"),
        names("python_free_flight_flat")
    );
}

#[test]
fn loops_and_conditions_unroll_in_order() {
    assert_eq!(
        lists("for i in range(1, 4):\n    L = DEFI_LIST_REEL(VALE=(i, 10. * i))\n"),
        vec![vec![1.0, 10.0], vec![2.0, 20.0], vec![3.0, 30.0]]
    );
    // if/elif/else on values known before the run; nested blocks; a
    // variable set in a loop keeps its last value after it, as in Python.
    let text = "\
N = 0
for i in range(5):
    if i % 2 == 0:
        N = N + i
    elif i == 3:
        pass
    else:
        L = DEFI_LIST_REEL(VALE=(i, i + 0.5))
L = DEFI_LIST_REEL(VALE=(N, i))
";
    // N = 0 + 2 + 4 and i = 4 (the checker does not order VALE; the run does).
    assert_eq!(lists(text), vec![vec![1.0, 1.5], vec![6.0, 4.0]]);
    // A body on the header's line, tuple unpacking, append, comprehension.
    let text = "\
a, b = 1, 2
P = []
for x, y in ((a, b), (3, 4)): P.append(x + y / 10.)
L = DEFI_LIST_REEL(VALE=P)
L = DEFI_LIST_REEL(VALE=[float(p) for p in range(3) if p != 1])
L = DEFI_LIST_REEL(VALE=sorted_list) if 0 else DEFI_LIST_REEL(VALE=(1., 2.))
";
    let e = check(&format!("DEBUT()\n{text}\nFIN()\n")).unwrap_err();
    assert!(
        e[0].message.contains("cannot be called here"),
        "{}",
        e[0].message
    );
    let text = &text[..text.rfind("L = DEFI_LIST_REEL(VALE=sorted").unwrap()];
    assert_eq!(lists(text), vec![vec![1.2, 3.4], vec![0.0, 2.0]]);
    // enumerate and zip, in the for that uses them, with a nested target
    // (`for i, (a, b) in ...`, a syntax error until probe13).
    let text = "\
for i, (a, b) in enumerate(zip((1., 2.), (10., 20.))):
    L = DEFI_LIST_REEL(VALE=(i, a, b))
";
    assert_eq!(
        lists(text),
        vec![vec![0.0, 1.0, 10.0], vec![1.0, 2.0, 20.0]]
    );
    let text = "\
for i, ab in enumerate(zip((1., 2.), (10., 20.))):
    a, b = ab
    L = DEFI_LIST_REEL(VALE=(i, a, b))
";
    assert_eq!(
        lists(text),
        vec![vec![0.0, 1.0, 10.0], vec![1.0, 2.0, 20.0]]
    );
    // imports.
    let text = "\
import math
from math import sqrt as racine, pi
import numpy as np
L = DEFI_LIST_REEL(VALE=(math.cos(pi), racine(4.), np.sqrt(9.), math.floor(5.5)))
";
    assert_eq!(lists(text), vec![vec![-1.0, 2.0, 3.0, 5.0]]);
    // math's names without an import, as code_aster's namespace has them
    // (its tests sdnv100a and sdnv108a write sqrt(...) and pi so); a
    // name the file binds is the file's.
    let text = "L = DEFI_LIST_REEL(VALE=(sqrt(4.), cos(pi), floor(2.5)))\n";
    assert_eq!(lists(text), vec![vec![2.0, -1.0, 2.0]]);
    let text = "pi = 3.\nL = DEFI_LIST_REEL(VALE=(pi, 2. * pi))\n";
    assert_eq!(lists(text), vec![vec![3.0, 6.0]]);
    // from code_aster.Commands import * is accepted before DEBUT.
    let c = check("from code_aster.Commands import *\nDEBUT()\nFIN()\n").unwrap();
    assert_eq!(c.commands.len(), 2);
}

#[test]
fn commands_in_loops_keep_their_own_lines() {
    let text = "DEBUT()\nfor k in (1, 2):\n    L = DEFI_LIST_REEL(VALE=(0., k))\nFIN()\n";
    let src = Source::new("t.comm", text);
    let c = check(text).unwrap();
    let lines: Vec<usize> = c
        .commands
        .iter()
        .map(|c| src.line_col(c.span.start).0)
        .collect();
    assert_eq!(lines, vec![1, 3, 3, 4]);
    let values: Vec<Vec<f64>> = c
        .commands
        .iter()
        .filter(|c| c.name == "DEFI_LIST_REEL")
        .map(|c| Args::reals(&c.args, "VALE"))
        .collect();
    assert_eq!(values, vec![vec![0.0, 1.0], vec![0.0, 2.0]]);
    // An error in a loop is reported once, at its line.
    let (m, l, c) = error("for k in (1, 2):\n    L = DEFI_LIST_REEL(VALE=(1., 'a'))");
    assert_eq!((l, c), (2, 34), "{m}");
    let ds = check("DEBUT()\nfor k in (1, 2, 3):\n    L = DEFI_LIST_REEL(VALEUR=k)\nFIN()\n")
        .unwrap_err();
    assert_eq!(
        ds.iter().filter(|d| d.message.contains("VALEUR")).count(),
        1
    );
}

/// `for M in (MA, MB): M = DEFI_GROUP(reuse=M, MAILLAGE=M, ...)`: the loop
/// name holds each concept in turn, and Python modifies that concept in
/// place; aster runs the command on the concept's own name (it refused the
/// loop, calling M "the concept MA ... not a concept").
#[test]
fn reuse_through_a_loop_name_modifies_the_concept_it_holds() {
    let text = "DEBUT()
MA = LIRE_MAILLAGE(FORMAT='MED')
MB = LIRE_MAILLAGE(FORMAT='MED', UNITE=21)
for M in (MA, MB):
    M = DEFI_GROUP(reuse=M, MAILLAGE=M, CREA_GROUP_NO=_F(TOUT_GROUP_MA='OUI'))
    T = DEFI_GROUP(reuse=M, MAILLAGE=M, CREA_GROUP_NO=_F(TOUT_GROUP_MA='OUI'))
FIN()
";
    let ds = check(text).unwrap_err();
    // Only the second form, which binds another name, is refused.
    assert!(
        ds.iter()
            .all(|d| d.message.contains("so the result must be assigned to")),
        "{ds:?}"
    );
    let text = text.replace("    T = DEFI_GROUP", "    M = DEFI_GROUP");
    let c = check(&text).unwrap();
    let runs: Vec<(String, Option<String>, Option<String>)> = c
        .commands
        .iter()
        .filter(|c| c.name == "DEFI_GROUP")
        .map(|c| {
            (
                c.result.as_ref().unwrap().name.clone(),
                c.reuse.clone(),
                c.args.concept("MAILLAGE").map(str::to_string),
            )
        })
        .collect();
    let on = |n: &str| (n.to_string(), Some(n.to_string()), Some(n.to_string()));
    assert_eq!(runs, vec![on("MA"), on("MA"), on("MB"), on("MB")]);
}

/// A command called in another's keyword runs first, as Python runs it, and
/// the keyword receives its concept; innermost first, once per loop pass.
#[test]
fn commands_inside_keywords_run_before_their_command() {
    let text = "DEBUT()\n\
for k in (1., 2.):
    LI = DEFI_LIST_INST(DEFI_LIST=_F(LIST_INST=DEFI_LIST_REEL(VALE=(0., k))))
F = CALC_FONCTION(COMB=_F(FONCTION=DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 0., 1., 2.)),
                          COEF=2.))
FIN()\n";
    let src = Source::new("t.comm", text);
    let c = check(text).unwrap_or_else(|ds| {
        panic!(
            "{}",
            ds.iter().map(|d| d.render(Some(&src))).collect::<String>()
        )
    });
    let names: Vec<&str> = c.commands.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "DEBUT",
            "DEFI_LIST_REEL",
            "DEFI_LIST_INST",
            "DEFI_LIST_REEL",
            "DEFI_LIST_INST",
            "DEFI_FONCTION",
            "CALC_FONCTION",
            "FIN"
        ]
    );
    // Each DEFI_LIST_INST gets the list made just before it, at its line.
    for i in [1, 3] {
        let inner = c.commands[i].result.as_ref().expect("named").name.clone();
        let outer = c.commands[i + 1].args.facts("DEFI_LIST")[0].concept("LIST_INST");
        assert_eq!(outer, Some(inner.as_str()));
        assert_eq!(
            c.commands[i].args.reals("VALE"),
            vec![0.0, (i / 2 + 1) as f64]
        );
        assert_eq!(src.line_col(c.commands[i].span.start), (3, 48));
    }
    let inner = c.commands[5].result.as_ref().unwrap().name.clone();
    assert_eq!(
        c.commands[6].args.facts("COMB")[0].concept("FONCTION"),
        Some(inner.as_str())
    );
    // Where Python may evaluate the call several times or not at all, the
    // result must be named first.
    for (text, col) in [
        ("L = DEFI_LIST_INST(DEFI_LIST=_F(LIST_INST=DEFI_LIST_REEL(VALE=(0., 1.)) if 1 else None))", 43),
        ("X = [DEFI_LIST_REEL(VALE=(0., k)) for k in (1., 2.)]", 6),
    ] {
        let (m, l, c) = error(text);
        assert!(m.contains("DEFI_LIST_REEL cannot be called here"), "{m}");
        assert_eq!((l, c), (1, col), "{m}");
    }
}

#[test]
fn what_needs_a_concept_content_is_refused_where_written() {
    let concept = "L = DEFI_LIST_REEL(VALE=(0., 1.))\n";
    for (text, msg, line, col) in [
        (
            format!("{concept}if L:\n    pass"),
            "a condition cannot test the concept L, whose content is not known before the study runs",
            2,
            4,
        ),
        (
            format!("{concept}for x in L:\n    pass"),
            "a loop cannot go through the concept L",
            2,
            10,
        ),
        (
            format!("{concept}N = len(L)"),
            "len() reads the concept L",
            2,
            9,
        ),
        (
            format!("{concept}T = 'R_%s' % L"),
            "the text of the concept L is not known before the study runs",
            2,
            5,
        ),
        (
            format!("{concept}B = L == L"),
            "comparing the concept L",
            2,
            5,
        ),
        (
            format!("{concept}M = [L]\nL = DEFI_LIST_REEL(VALE=(0., 2.))\nL2 = DEFI_LIST_REEL(VALE=(0., 1.))\nIMPR_TABLE(TABLE=M[0])"),
            "this value holds the concept L as it was before L was defined again",
            5,
            18,
        ),
    ] {
        let (m, l, c) = error(&text);
        assert!(m.contains(msg), "{text}: {m}");
        assert_eq!((l, c), (line, col), "{text}: {m}");
    }
}

#[test]
fn python_mistakes_are_located_errors() {
    for (text, msg, line, col) in [
        (
            "import os",
            "module 'os' is not available in command files",
            1,
            8,
        ),
        (
            "from numpy import *",
            "'from numpy import *' is not supported",
            1,
            6,
        ),
        (
            "from math import sqrtt",
            "math.sqrtt is not available",
            1,
            18,
        ),
        (
            "from code_aster.Commands import DEBUTT",
            "code_aster.Commands has no command DEBUTT",
            1,
            33,
        ),
        (
            "a, b = 1, 2, 3",
            "cannot unpack a tuple into 2 names: it has 3 items",
            1,
            8,
        ),
        (
            "L = (1, 2)\nL.append(3)",
            "append needs a list, and L is a tuple",
            2,
            1,
        ),
        (
            "L = []\nM = L\nL.append(3)",
            "L is the same list as M",
            3,
            1,
        ),
        (
            "L = [1]\nfor x in L:\n    L.append(x)",
            "while it is being looped over",
            3,
            5,
        ),
        (
            "for i in range(2000000):\n    pass",
            "a range of more than 1000000 values",
            1,
            10,
        ),
        (
            "for i in range(1000):\n    for j in range(1001):\n        pass",
            "the loops and comprehensions of the file run more than 1000000 iterations",
            2,
            14,
        ),
        (
            "N = 3\nfor i in N:\n    pass",
            "cannot loop over the integer 3",
            2,
            10,
        ),
        (
            "if 1 < 'a':\n    pass",
            "'<' is not supported between the integer 1 and the text 'a'",
            1,
            4,
        ),
        (
            "T = 'G_%d' % 'x'",
            "%d format: a real number is required, not str",
            1,
            5,
        ),
        (
            "Z = zip((1,), (2,))",
            "a zip object cannot be kept in a name",
            1,
            5,
        ),
    ] {
        let (m, l, c) = error(text);
        assert!(m.contains(msg), "{text}: {m}");
        assert_eq!((l, c), (line, col), "{text}: {m}");
    }
}

/// Loop targets in parentheses or brackets unpack as in Python, in `for`
/// blocks and comprehensions: `(a, b)` and `[a, b]` take pairs apart,
/// `(a)` is the name `a`, `[f]` unpacks a one-item sequence. The values
/// are Python's: 1·2 + 3·4 + 5·6 + (1 + 2) + 7 = 54, [2, 12], [11].
#[test]
fn parenthesised_and_bracketed_loop_targets_unpack_as_in_python() {
    let text = "S = 0.
for (a, b) in ((1., 2.), (3., 4.)):
    S = S + a * b
for [c, d] in [(5., 6.)]:
    S = S + c * d
for (e) in (1., 2.):
    S = S + e
for [f] in ((7.,),):
    S = S + f
L = DEFI_LIST_REEL(VALE=[S] + [a * b for (a, b) in ((1., 2.), (3., 4.))]
                   + [c + d for [c, d] in [(5., 6.)] if c > 0.])
";
    assert_eq!(lists(text), vec![vec![54.0, 2.0, 12.0, 11.0]]);
    let (m, line, col) = error("for [f] in (7., 8.):\n    pass\n");
    assert!(
        m.contains("cannot loop over the real 7.0") && (line, col) == (1, 13),
        "{m} at {line}:{col}"
    );
}

/// A loop of appends builds its list in place: 200 000 appends give the
/// list (the checker copied the whole list at each append, so a fuzzed
/// study's range(1000000) ran for an hour in the fuzz test).
#[test]
fn appends_in_a_long_loop_build_the_list() {
    let text = "\
P = []
for i in range(200000):
    P.append(i % 7)
L = DEFI_LIST_REEL(VALE=(float(len(P)), float(P[-1]), float(P[123456])))
";
    assert_eq!(
        lists(text),
        vec![vec![200000.0, (199999 % 7) as f64, (123456 % 7) as f64]]
    );
}

/// A FORMULE reading a command-file variable keeps the value it had then;
/// rebinding the variable later is a warning (code_aster up to 13 would
/// read the new value when evaluating the formula, 14+ only FORMULE's
/// keywords), located at the rebinding, once per formula. Passing the
/// value as a keyword, or defining the formula again in a loop over the
/// variable, is not.
#[test]
fn formula_variables_rebound_later_are_warned() {
    let text = "DEBUT()
A0 = 3.
F = FORMULE(VALE='A0*INST', NOM_PARA='INST')
G = FORMULE(VALE='A0*INST', NOM_PARA='INST', A0=A0)
A0 = 5.
A0 = 7.
for k in range(3):
    H = FORMULE(VALE='k*INST', NOM_PARA='INST')
FIN()
";
    let c = check(text).unwrap_or_else(|d| panic!("{d:?}"));
    let w: Vec<&Diagnostic> = c.warnings.iter().collect();
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(
        w[0].message,
        "A0 is bound again after the FORMULE F read it: F keeps the real 3.0"
    );
    let src = Source::new("t.comm", text);
    assert!(
        w[0].render(Some(&src)).contains("t.comm:5:1"),
        "{}",
        w[0].render(Some(&src))
    );
}

/// What code_aster files written for code_aster meet here (probe s8c over
/// 20 real test files): a code_aster command aster lacks is named as such,
/// not as a typo of another command; an unknown keyword is reported once
/// (not again as "at least one of ... must be given"); LIRE_MAILLAGE in a
/// format other than MED stops at check, not when the study runs;
/// DEBUT(PAR_LOT=...) of code_aster 14 is accepted.
#[test]
fn code_aster_files_meet_clear_messages() {
    // (DEFI_LIST_ENTI was this test's command until aster implemented it.)
    let full =
        "DEBUT()\nN = DEFI_NAPPE(NOM_PARA='AMOR', PARA=(0.01, 0.02), FONCTION=(F1, F2))\nFIN()\n";
    let ds = check(full).expect_err("DEFI_NAPPE");
    assert_eq!(ds.len(), 1, "{ds:?}");
    assert_eq!(ds[0].message, "unknown command DEFI_NAPPE");
    assert!(ds[0].suggestion.is_none(), "{:?}", ds[0].suggestion);
    assert!(
        ds[0]
            .notes
            .iter()
            .any(|n| n.contains("a code_aster command that aster does not implement")),
        "{:?}",
        ds[0].notes
    );
    let full = "DEBUT()\nR = CALC_NO(RESULTAT=R0)\nFIN()\n";
    let ds = check(full).expect_err("CALC_NO");
    assert!(
        ds[0]
            .notes
            .iter()
            .any(|n| n.contains("replaced by CALC_CHAMP")),
        "{:?}",
        ds[0].notes
    );

    // Keywords code_aster removed: the note says what replaced them.
    for (full, what, by) in [
        (
            "DEBUT()\nR = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=C),\n\
             COMP_INCR=_F(RELATION='VMIS_ISOT_LINE'), INCREMENT=_F(LIST_INST=L))\nFIN()\n",
            "COMP_INCR",
            "it is now COMPORTEMENT",
        ),
        (
            "DEBUT()\nC = AFFE_CHAR_MECA(MODELE=MO, LIAISON_UNILATER=_F(GROUP_NO='A', NOM_CMP='DY',\n\
             COEF_IMPO=0., COEF_MULT=1.))\nFIN()\n",
            "LIAISON_UNILATER",
            "DEFI_CONTACT(FORMULATION='LIAISON_UNIL'",
        ),
    ] {
        let ds = check(full).expect_err(what);
        let d = ds
            .iter()
            .find(|d| d.message.starts_with(&format!("unknown keyword {what}")))
            .unwrap_or_else(|| panic!("{ds:?}"));
        assert!(d.notes.iter().any(|n| n.contains(by)), "{:?}", d.notes);
        assert!(d.suggestion.is_none(), "{:?}", d.suggestion);
    }

    let full = "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED')\n\
                MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))\n\
                CH = AFFE_CHAR_MECA(MODELE=MO, LIAISON_DDL=_F(GROUP_NO=('A', 'B'), DDL=('DX', 'DX'), COEF_MULT=(1., -1.), COEF_IMPO=0.))\n\
                FIN()\n";
    let ds = check(full).expect_err("LIAISON_DDL");
    assert_eq!(ds.len(), 1, "{ds:?}");
    assert!(
        ds[0].message.starts_with("unknown keyword LIAISON_DDL"),
        "{}",
        ds[0].message
    );

    let (m, l, c) = error("MA = LIRE_MAILLAGE(FORMAT='GIBI', UNITE=20)");
    assert_eq!(
        (m.as_str(), l, c),
        (
            "not implemented yet: LIRE_MAILLAGE/FORMAT='GIBI' (FORMAT='MED' and 'ASTER' are read)",
            1,
            27
        )
    );

    let c = check("DEBUT(PAR_LOT='NON')\nFIN()\n").unwrap();
    assert_eq!(c.commands.len(), 2);

    // A value code_aster removed: the note names its replacement (probe
    // h_frot: ssnv503b of 2013).
    let full = "DEBUT()\nCK = DEFI_CONTACT(MODELE=MO, FORMULATION='DISCRETE', ZONE=_F(GROUP_MA_MAIT='A', GROUP_MA_ESCL='B', ALGO_CONT='LAGRANGIEN'))\nFIN()\n";
    let ds = check(full).expect_err("LAGRANGIEN");
    let d = ds
        .iter()
        .find(|d| d.keyword.as_deref() == Some("ZONE/ALGO_CONT"))
        .unwrap_or_else(|| panic!("{ds:?}"));
    assert!(
        d.notes
            .iter()
            .any(|n| n.contains("removed from code_aster itself: write 'CONTRAINTE'")),
        "{:?}",
        d.notes
    );
    assert!(d.suggestion.is_none(), "{:?}", d.suggestion);

    // Keywords and values aster does not build stop the check, before any
    // command runs (probe h_gdef: code_aster's ssnv112 and ssnp159a passed
    // `aster check` and stopped in STAT_NON_LINE).
    let head = "DEBUT()\nMA = LIRE_MAILLAGE(FORMAT='MED')\n\
                MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT='OUI', PHENOMENE='MECANIQUE', MODELISATION='3D'))\n\
                MAT = DEFI_MATERIAU(ELAS=_F(E=1., NU=0., RHO=1.))\n\
                CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT='OUI', MATER=MAT))\n\
                C = AFFE_CHAR_MECA(MODELE=MO, DDL_IMPO=_F(TOUT='OUI', DX=0.))\n\
                L = DEFI_LIST_REEL(DEBUT=0., INTERVALLE=_F(JUSQU_A=1., NOMBRE=1))\n";
    for (body, want) in [
        (
            "R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=C),\n\
             INCREMENT=_F(LIST_INST=L), CONVERGENCE=_F(RESI_REFE_RELA=1.E-3, SIGM_REFE=1.))\nFIN()\n",
            "not implemented yet: STAT_NON_LINE/CONVERGENCE/RESI_REFE_RELA (give RESI_GLOB_RELA or RESI_GLOB_MAXI)",
        ),
        (
            "R = DYNA_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=C, TYPE_CHARGE='DIDI'),\n\
             INCREMENT=_F(LIST_INST=L), SCHEMA_TEMPS=_F(SCHEMA='NEWMARK', FORMULATION='DEPLACEMENT'))\nFIN()\n",
            "not implemented yet: DYNA_NON_LINE/EXCIT/TYPE_CHARGE='DIDI' (loads are dead, FIXE_CSTE, built on the initial geometry)",
        ),
        (
            "R0 = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=C), INCREMENT=_F(LIST_INST=L))\n\
             R = STAT_NON_LINE(MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=C),\n\
             ETAT_INIT=_F(EVOL_NOLI=R0, NUME_DIDI=2), INCREMENT=_F(LIST_INST=L))\nFIN()\n",
            "not implemented yet: STAT_NON_LINE/ETAT_INIT/NUME_DIDI (no TYPE_CHARGE='DIDI' load)",
        ),
    ] {
        let full = format!("{head}{body}");
        let ds = check(&full).expect_err(want);
        assert!(ds.iter().any(|d| d.message == want), "{ds:?}");
    }
}
