//! code_aster commands that aster does not have.
//!
//! Why: a file written for code_aster that calls one of these got
//! "unknown command DEFI_NAPPE, did you mean DEFI_FONCTION?", which
//! reads as a typo and suggests a command that does something else (probe
//! s8c over 20 real code_aster test files: 16 hit one). Named here, the
//! message says what it is. The names are those of code_aster's command
//! catalogue (facts, not code); the list is not complete.

/// Commands replaced in code_aster itself, with their replacement.
const OBSOLETE: &[(&str, &str)] = &[
    ("CALC_NO", "CALC_CHAMP"),
    ("CALC_ELEM", "CALC_CHAMP"),
    ("DEFI_CONTACT_2", "DEFI_CONTACT"),
];

/// Commands of code_aster that aster does not implement.
const NOT_IMPLEMENTED: &[&str] = &[
    "AFFE_CARA_ELEM",
    "AFFE_CHAR_ACOU",
    "AFFE_CHAR_THER",
    "AFFE_CHAR_THER_F",
    "ASSEMBLAGE",
    "ASSE_MATRICE",
    "ASSE_VECTEUR",
    "CALC_CHAR_SEISME",
    "CALC_ERREUR",
    "CALC_EUROPLEXUS",
    "CALC_FATIGUE",
    "CALC_FONC_INTERP",
    "CALC_G",
    "CALC_INTE_SPEC",
    "CALC_MATR_ELEM",
    "CALC_META",
    "CALC_MODES",
    "CALC_PRESSION",
    "CALC_SPEC",
    "CALC_STABILITE",
    "CALC_VECT_ELEM",
    "COMB_MATR_ASSE",
    "CREA_RESU",
    "DEFI_BASE_MODALE",
    "DEFI_CABLE_BP",
    "DEFI_COMPOR",
    "DEFI_FISS_XFEM",
    "DEFI_FOND_FISS",
    "DEFI_GEOM_FIBRE",
    "DEFI_GLRC",
    "DEFI_INTE_SPEC",
    "DEFI_MATER_GC",
    "DEFI_NAPPE",
    "DEFI_OBSTACLE",
    "DEFI_SQUELETTE",
    "DYNA_LINE_HARM",
    "DYNA_LINE_TRAN",
    "DYNA_VIBRA",
    "EXEC_LOGICIEL",
    "EXTR_RESU",
    "EXTR_TABLE",
    "IMPR_CO",
    "IMPR_GENE",
    "INFO_EXEC_ASTER",
    "INFO_RESU",
    "LIRE_CHAMP",
    "LIRE_FONCTION",
    "LIRE_RESU",
    "LIRE_TABLE",
    "MACRO_MATR_ASSE",
    "MACR_ADAP_MAIL",
    "MACR_CARA_POUTRE",
    "MACR_ELEM_STAT",
    "MACR_LIGN_COUPE",
    "MACR_RECAL",
    "MECA_NON_LINE",
    "MODE_ITER_SIMULT",
    "MODE_NON_LINE",
    "MODE_STATIQUE",
    "MODI_MODELE_XFEM",
    "MODI_REPERE",
    "NORM_MODE",
    "NUME_DDL",
    "POST_CHAMP",
    "POST_DYNA_ALEA",
    "POST_FATIGUE",
    "POST_GENE_PHYS",
    "POST_K1_K2_K3",
    "POST_MAIL_XFEM",
    "POST_NEWMARK",
    "POST_RCCM",
    "PROJ_BASE",
    "PROJ_CHAMP",
    "RECU_GENE",
    "REST_GENE_PHYS",
    "TEST_FICHIER",
    "THER_LINEAIRE",
    "THER_NON_LINE",
];

/// Keywords that code_aster itself removed or renamed, by command ("" for
/// every command), with what replaced them: a file written for an older
/// code_aster got a bare "unknown keyword" (probes h_si and h_unil over
/// code_aster's own test files of 2008-2013).
const REMOVED_KEYWORDS: &[(&str, &str, &str)] = &[
    ("", "COMP_ELAS", "COMPORTEMENT (RELATION='ELAS', ...)"),
    ("", "COMP_INCR", "COMPORTEMENT"),
    (
        "AFFE_CHAR_MECA",
        "CONTACT",
        "DEFI_CONTACT, given to STAT_NON_LINE / DYNA_NON_LINE by CONTACT=",
    ),
    (
        "AFFE_CHAR_MECA",
        "LIAISON_UNILATER",
        "DEFI_CONTACT(FORMULATION='LIAISON_UNIL', ZONE=_F(...)), given to STAT_NON_LINE / DYNA_NON_LINE by CONTACT=",
    ),
    ("TEST_RESU", "VALE", "VALE_CALC (and VALE_REFE with REFERENCE)"),
    ("TEST_TABLE", "VALE", "VALE_CALC (and VALE_REFE with REFERENCE)"),
];

/// Values that code_aster itself removed, by command and keyword, with
/// what replaced them (probe h_frot: ssnv503b of 2013 gives
/// ALGO_CONT='LAGRANGIEN').
const REMOVED_VALUES: &[(&str, &str, &str, &str)] = &[
    (
        "DEFI_CONTACT",
        "ALGO_CONT",
        "LAGRANGIEN",
        "'CONTRAINTE' (the active set of FORMULATION='DISCRETE') or FORMULATION='CONTINUE' (ALGO_CONT='STANDARD')",
    ),
    (
        "DEFI_CONTACT",
        "ALGO_FROT",
        "LAGRANGIEN",
        "'PENALISATION' (FORMULATION='DISCRETE') or FORMULATION='CONTINUE' (ALGO_FROT='STANDARD')",
    ),
];

/// What became of value `value` of keyword `name` of `command` in
/// code_aster, when code_aster removed it.
pub fn removed_value(command: &str, name: &str, value: &str) -> Option<String> {
    REMOVED_VALUES
        .iter()
        .find(|(c, k, v, _)| *c == command && *k == name && *v == value)
        .map(|(_, _, _, by)| {
            format!("{name}='{value}' is an old code_aster value, removed from code_aster itself: write {by}")
        })
}

/// What became of keyword `name` of `command` in code_aster, when
/// code_aster removed or renamed it.
pub fn removed_keyword(command: &str, name: &str) -> Option<String> {
    REMOVED_KEYWORDS
        .iter()
        .find(|(c, k, _)| (c.is_empty() || *c == command) && *k == name)
        .map(|(_, _, by)| {
            format!("{name} is an old code_aster keyword, removed from code_aster itself: it is now {by}")
        })
}

/// What a call of `name` is, when it is a code_aster command aster lacks.
pub fn describe(name: &str) -> Option<String> {
    if let Some((_, by)) = OBSOLETE.iter().find(|(n, _)| *n == name) {
        return Some(format!(
            "{name} is an obsolete code_aster command, replaced by {by} in code_aster itself: write {by}(...)"
        ));
    }
    NOT_IMPLEMENTED.contains(&name).then(|| {
        format!(
            "{name} is a code_aster command that aster does not implement (`aster doc commands` lists the commands aster has)"
        )
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn lists_are_sorted_and_distinct() {
        let n = super::NOT_IMPLEMENTED;
        assert!(n.windows(2).all(|w| w[0] < w[1]), "sort the list");
        for (o, _) in super::OBSOLETE {
            assert!(!n.contains(o));
        }
    }
}
