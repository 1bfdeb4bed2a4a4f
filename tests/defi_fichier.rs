//! DEFI_FICHIER: a logical unit tied to a named file receives what the
//! commands write to that unit; LIBERER writes it at once; APPEND keeps
//! what the file held, NEW starts it empty; refused input is located.

use std::path::{Path, PathBuf};
use std::process::Command;

fn study_dir(tag: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("defi_fichier_{tag}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `body` (between DEBUT and FIN) in a fresh directory: (exit code,
/// terminal output, directory).
fn run(tag: &str, body: &str) -> (i32, String, PathBuf) {
    let dir = study_dir(tag);
    let comm = dir.join("t.comm");
    std::fs::write(&comm, format!("DEBUT()\n{body}FIN()\n")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_aster"))
        .arg("run")
        .arg(&comm)
        .output()
        .unwrap();
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    (out.status.code().unwrap_or(-1), text, dir)
}

const FUNCTIONS: &str = "F1 = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 1., 1., 3.))
F2 = DEFI_FONCTION(NOM_PARA='INST', VALE=(0., 7., 2., 9.))
";

#[test]
fn a_unit_writes_to_its_file_and_append_keeps_what_it_held() {
    let body = format!(
        "{FUNCTIONS}DEFI_FICHIER(ACTION='ASSOCIER', UNITE=38, FICHIER='REPE_OUT/courbes.txt')
IMPR_FONCTION(FORMAT='TABLEAU', UNITE=38, COURBE=_F(FONCTION=F1))
DEFI_FICHIER(ACTION='LIBERER', UNITE=38)
DEFI_FICHIER(UNITE=38, FICHIER='REPE_OUT/courbes.txt', ACCES='APPEND')
IMPR_FONCTION(FORMAT='TABLEAU', UNITE=38, COURBE=_F(FONCTION=F2))
DEFI_FICHIER(ACTION='LIBERER', UNITE=38)
DEFI_FICHIER(UNITE=39, FICHIER='neuf.txt')
IMPR_FONCTION(FORMAT='TABLEAU', UNITE=39, COURBE=_F(FONCTION=F1))
DEFI_FICHIER(UNITE=39, FICHIER='neuf.txt', ACCES='NEW')
IMPR_FONCTION(FORMAT='TABLEAU', UNITE=39, COURBE=_F(FONCTION=F2))
"
    );
    let (code, term, dir) = run("append", &body);
    assert_eq!(code, 0, "{term}");
    let both = std::fs::read_to_string(dir.join("REPE_OUT/courbes.txt")).unwrap();
    // F1's ordinates 1, 3 then F2's 7, 9, in that order, in one file
    let at = |s: &str, v: &str| s.find(v).unwrap_or_else(|| panic!("{v} not in\n{s}"));
    assert!(
        at(&both, "3.00000E+00") < at(&both, "7.00000E+00"),
        "{both}"
    );
    assert!(at(&both, "9.00000E+00") > 0, "{both}");
    // NEW started neuf.txt again: F2 only
    let new = std::fs::read_to_string(dir.join("neuf.txt")).unwrap();
    assert!(
        new.contains("9.00000E+00") && !new.contains("3.00000E+00"),
        "{new}"
    );
    // nothing went to fort.38 / fort.39
    assert!(!dir.join("fort.38").exists() && !dir.join("fort.39").exists());
}

#[test]
fn refused_input_is_located() {
    for (tag, call, what) in [
        (
            "old",
            "DEFI_FICHIER(UNITE=40, FICHIER='absent.txt', ACCES='OLD')",
            "ACCES='OLD' needs the file",
        ),
        (
            "resu",
            "DEFI_FICHIER(UNITE=8, FICHIER='x.txt')",
            "unit 8 is the result (.resu) file",
        ),
        (
            "no_unit",
            "DEFI_FICHIER(FICHIER='x.txt')",
            "not implemented yet: DEFI_FICHIER/UNITE",
        ),
        (
            "no_file",
            "DEFI_FICHIER(UNITE=41)",
            "ACTION='ASSOCIER' needs FICHIER",
        ),
    ] {
        let (code, term, _) = run(tag, &format!("{call}\n"));
        assert_eq!(code, 1, "{tag}: {term}");
        assert!(term.contains(what), "{tag}: {term}");
        assert!(term.contains("t.comm:2"), "{tag}: {term}");
        assert!(!term.contains("panicked"), "{tag}: {term}");
    }
}
