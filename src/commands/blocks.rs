//! Factor blocks shared by several commands (code_aster's `Cata/Commons`),
//! plus the small helpers that keep each command declaration close to its
//! code_aster catalogue.
//!
//! A keyword that code_aster declares twice at one level (e.g. `PRECISION`
//! under `CRITERE='RELATIF'` with a default and under `'ABSOLU'` without)
//! is declared here the same way, in blocks whose conditions exclude each
//! other; `tests/catalog_doc.rs` checks that no two declarations of one
//! name can be active together.

use crate::catalog::schema::*;
use crate::concepts::ConceptType as C;

// ---------------------------------------------------------------------------
// Literals and conditions, short.

/// The result types the post-processing commands read (RESULTAT=): the
/// nonlinear evolutions and MECA_STATIQUE's linear ones hold the same
/// fields.
pub const RESULTS: &[C] = &[C::EvolNoli, C::EvolElas];

pub fn r(v: f64) -> Lit {
    Lit::Real(v)
}
pub fn i(v: i64) -> Lit {
    Lit::Int(v)
}
pub fn t(v: &'static str) -> Lit {
    Lit::Text(v)
}
pub fn eq(key: &'static str, v: &'static str) -> Cond {
    Cond::Eq(key, Lit::Text(v))
}
pub fn eq_int(key: &'static str, v: i64) -> Cond {
    Cond::Eq(key, Lit::Int(v))
}
pub fn is_in(key: &'static str, vs: &[&'static str]) -> Cond {
    Cond::In(key, vs.iter().map(|v| Lit::Text(v)).collect())
}
pub fn present(key: &'static str) -> Cond {
    Cond::Present(key)
}
pub fn absent(key: &'static str) -> Cond {
    Cond::Absent(key)
}
pub fn and(cs: Vec<Cond>) -> Cond {
    Cond::And(cs)
}
pub fn or(cs: Vec<Cond>) -> Cond {
    Cond::Or(cs)
}
pub fn not(c: Cond) -> Cond {
    Cond::Not(Box::new(c))
}

// ---------------------------------------------------------------------------
// Simple keywords that recur everywhere.

/// A text keyword taking 'OUI' or 'NON', with its default.
pub fn oui_non(name: &'static str, default: &'static str) -> Simple {
    text(name).into(&["OUI", "NON"]).default(t(default))
}
/// `TOUT='OUI'`: the whole mesh (or model).
pub fn tout() -> Keyword {
    text("TOUT")
        .into(&["OUI"])
        .doc("'OUI' selects every cell of the mesh")
        .kw()
}
pub fn group_ma() -> Keyword {
    text("GROUP_MA").many().doc("cell groups").kw()
}
pub fn group_no() -> Keyword {
    text("GROUP_NO").many().doc("node groups").kw()
}
/// Cells by name: deprecated in code_aster (hidden), groups are preferred.
pub fn maille() -> Keyword {
    text("MAILLE")
        .many()
        .hidden()
        .doc("cells by name (deprecated: use GROUP_MA)")
        .kw()
}
/// Nodes by name: deprecated in code_aster (hidden), groups are preferred.
pub fn noeud() -> Keyword {
    text("NOEUD")
        .many()
        .hidden()
        .doc("nodes by name (deprecated: use GROUP_NO)")
        .kw()
}
/// `INFO`: verbosity of the message file, 1 (default) or 2.
pub fn info() -> Keyword {
    int("INFO")
        .default(i(1))
        .into_ints(&[1, 2])
        .doc("verbosity of the message file: 1 or 2 (more detail)")
        .kw()
}
pub fn titre() -> Keyword {
    text("TITRE")
        .many()
        .doc("title lines of the produced concept")
        .kw()
}
/// The time/parameter search tolerance of access keywords: `CRITERE`
/// then `PRECISION`, defaulted when relative, compulsory when absolute.
pub fn critere_precision(default: f64) -> Vec<Keyword> {
    vec![
        text("CRITERE")
            .into(&["RELATIF", "ABSOLU"])
            .default(t("RELATIF"))
            .doc("whether PRECISION is relative to the searched value or absolute")
            .kw(),
        block(
            "b_prec_rela",
            eq("CRITERE", "RELATIF"),
            vec![real("PRECISION")
                .default(r(default))
                .doc("relative search tolerance")
                .kw()],
        )
        .kw(),
        block(
            "b_prec_abso",
            eq("CRITERE", "ABSOLU"),
            vec![real("PRECISION")
                .required()
                .doc("absolute search tolerance")
                .kw()],
        )
        .kw(),
    ]
}

/// Field names of a nonlinear result (`evol_noli`) that commands may read.
pub const NOM_CHAM_RESU: &[&str] = &[
    "DEPL",
    "VITE",
    "ACCE",
    "SIEF_ELGA",
    "SIGM_ELGA",
    "VARI_ELGA",
    "EPSI_ELGA",
    "SIEF_ELNO",
    "SIGM_ELNO",
    "VARI_ELNO",
    "EPSI_ELNO",
    "SIEF_NOEU",
    "SIGM_NOEU",
    "VARI_NOEU",
    "EPSI_NOEU",
    "EPSG_ELGA",
    "EPSG_ELNO",
    "EPSG_NOEU",
    "EPSL_ELGA",
    "EPSL_ELNO",
    "EPSL_NOEU",
    "EPSP_ELGA",
    "EPSP_ELNO",
    "EPSP_NOEU",
    "SIEQ_ELGA",
    "SIEQ_ELNO",
    "SIEQ_NOEU",
    "EPEQ_ELGA",
    "EPEQ_ELNO",
    "EPEQ_NOEU",
    "ENEL_ELGA",
    "ENEL_ELNO",
    "ENEL_NOEU",
    "FORC_NODA",
    "REAC_NODA",
    "CONT_NOEU",
    "COMPORTEMENT",
];

/// The constitutive laws aster knows by name (code_aster's `C_RELATION`
/// restricted to the laws of the impact studies); the law registry
/// decides which ones actually run.
pub const RELATIONS: &[&str] = &[
    "ELAS",
    "VMIS_ISOT_LINE",
    "VMIS_ISOT_TRAC",
    "VMIS_ISOT_PUIS",
    "VMIS_CINE_LINE",
    "VMIS_JOHN_COOK",
];

/// Solid modelisations of `AFFE_MODELE` (code_aster's list restricted to
/// continuum mechanics; shells, beams and THM are outside aster's scope).
pub const MODELISATIONS: &[&str] = &[
    "3D",
    "3D_SI",
    "AXIS",
    "AXIS_SI",
    "D_PLAN",
    "D_PLAN_SI",
    "C_PLAN",
    "C_PLAN_SI",
];

/// Components of the displacement quantity (DEPL_R) a user can name.
pub const CMP_DEPL: &[&str] = &["DX", "DY", "DZ", "DRX", "DRY", "DRZ"];

// ---------------------------------------------------------------------------
// Cata/Commons: nonlinear solver blocks.

/// `COMPORTEMENT` (`C_COMPORTEMENT`): the law and strain measure per cell
/// group; later occurrences override earlier ones on common cells.
pub fn c_comportement() -> Keyword {
    fact(
        "COMPORTEMENT",
        vec![
            tout(),
            group_ma(),
            maille(),
            text("RELATION")
                .into(RELATIONS)
                .default(t("ELAS"))
                .doc("constitutive law")
                .kw(),
            text("DEFORMATION")
                .into(&["PETIT", "PETIT_REAC", "GROT_GDEP", "SIMO_MIEHE", "GDEF_LOG"])
                .default(t("PETIT"))
                .doc("strain measure: small, updated small, Green-Lagrange, Simo-Miehe multiplicative or logarithmic")
                .kw(),
            real("RESI_INTE_RELA")
                .default(r(1e-6))
                .doc("relative tolerance of the local law integration")
                .kw(),
            int("ITER_INTE_MAXI")
                .default(i(20))
                .doc("maximum iterations of the local law integration")
                .kw(),
            block(
                "b_redec_local",
                is_in("DEFORMATION", &["PETIT", "PETIT_REAC", "GROT_GDEP"]),
                vec![int("ITER_INTE_PAS")
                    .default(i(0))
                    .doc("local sub-stepping of the law integration (0: none)")
                    .kw()],
            )
            .kw(),
            text("ALGO_INTE")
                .into(&[
                    "ANALYTIQUE",
                    "SECANTE",
                    "DEKKER",
                    "NEWTON_1D",
                    "BRENT",
                    "NEWTON",
                    "NEWTON_RELI",
                    "NEWTON_PERT",
                    "RUNGE_KUTTA",
                    "SPECIFIQUE",
                    "SEMI_EXPLICITE",
                    "BASCULE_EXPLICITE",
                    "SANS_OBJET",
                ])
                .doc("local integration algorithm; absent: the law's first one (ANALYTIQUE, BRENT for VMIS_JOHN_COOK, DEKKER for VMIS_ISOT_PUIS)")
                .kw(),
            text("TYPE_MATR_TANG")
                .into(&["PERTURBATION", "VERIFICATION"])
                .doc("tangent by finite differences, or check of the analytic one")
                .kw(),
            block(
                "b_perturb",
                present("TYPE_MATR_TANG"),
                vec![real("VALE_PERT_RELA").default(r(1e-5)).kw()],
            )
            .kw(),
            block(
                "b_radi",
                absent("TYPE_MATR_TANG"),
                vec![real("RESI_RADI_RELA")
                    .doc("alarm threshold on the radial-return angle")
                    .kw()],
            )
            .kw(),
            oui_non("SYME_MATR_TANG", "OUI")
                .doc("symmetrise the local tangent")
                .kw(),
            real("PARM_THETA")
                .default(r(1.0))
                .min_val(0.0)
                .max_val(1.0)
                .doc("theta of the local time integration")
                .kw(),
            oui_non("REGU_VISC", "NON").kw(),
            block(
                "b_crirupt",
                is_in("RELATION", &["VMIS_ISOT_LINE", "VMIS_ISOT_TRAC"]),
                vec![text("POST_ITER")
                    .into(&["CRIT_RUPT"])
                    .doc("element deletion on a critical stress")
                    .kw()],
            )
            .kw(),
        ],
    )
    .many()
    .rules(vec![present_absent("TOUT", &["GROUP_MA", "MAILLE"])])
    .doc("constitutive law per cell group; later occurrences override earlier ones; cells not covered get ELAS/PETIT")
    .kw()
}

/// `NEWTON` (`C_NEWTON`) of STAT_NON_LINE and DYNA_NON_LINE: REAC_ITER = 1
/// by default in both (code_aster 15+; its 2015 catalogue had 0 for both:
/// semantics.md §8.4 is the version this project follows).
pub fn c_newton() -> Keyword {
    newton_with(1)
}

fn newton_with(reac_iter: i64) -> Keyword {
    fact(
        "NEWTON",
        vec![
            int("REAC_INCR")
                .default(i(1))
                .min_val(0.0)
                .doc("reassemble the matrix at the prediction every REAC_INCR steps (0: never)")
                .kw(),
            text("PREDICTION")
                .into(&["DEPL_CALCULE", "TANGENTE", "ELASTIQUE", "EXTRAPOLE"])
                .not_built(
                    &["DEPL_CALCULE", "EXTRAPOLE"],
                    "the prediction uses the matrix TANGENTE or ELASTIQUE",
                )
                .doc("prediction matrix (TANGENTE or ELASTIQUE; absent: the value of MATRICE)")
                .kw(),
            text("MATRICE")
                .into(&["TANGENTE", "ELASTIQUE"])
                .default(t("TANGENTE"))
                .doc("matrix of the Newton iterations")
                .kw(),
            real("PAS_MINI_ELAS").min_val(0.0).kw(),
            int("REAC_ITER")
                .default(i(reac_iter))
                .min_val(0.0)
                .doc("reassemble every REAC_ITER iterations (0: keep the prediction matrix)")
                .kw(),
            int("REAC_ITER_ELAS").default(i(0)).min_val(0.0).kw(),
            concept("EVOL_NOLI", &[C::EvolNoli])
                .doc("result giving the prediction for PREDICTION='DEPL_CALCULE'")
                .kw(),
            oui_non("MATR_RIGI_SYME", "NON")
                .doc("symmetrise the assembled stiffness (K+K^T)/2; forced by discrete contact")
                .kw(),
        ],
    )
    .defaulted()
    .doc("Newton method settings")
    .kw()
}

/// `CONVERGENCE` (`C_CONVERGENCE`).
pub fn c_convergence() -> Keyword {
    let refe = |n: &'static str| real(n).kw();
    fact(
        "CONVERGENCE",
        vec![
            block(
                "b_refe_rela",
                present("RESI_REFE_RELA"),
                vec![
                    refe("SIGM_REFE"),
                    refe("EPSI_REFE"),
                    refe("DEPL_REFE"),
                    refe("VARI_REFE"),
                    refe("LAGR_REFE"),
                    refe("EFFORT_REFE"),
                    refe("MOMENT_REFE"),
                ],
            )
            .rules(vec![au_moins_un(&[
                "SIGM_REFE",
                "EPSI_REFE",
                "DEPL_REFE",
                "VARI_REFE",
                "LAGR_REFE",
                "EFFORT_REFE",
                "MOMENT_REFE",
            ])])
            .kw(),
            real("RESI_REFE_RELA")
                .doc("residual relative to reference forces built from the *_REFE values")
                .not_built_any("give RESI_GLOB_RELA or RESI_GLOB_MAXI")
                .kw(),
            real("RESI_GLOB_MAXI")
                .doc("absolute residual: max over dofs of |R|")
                .kw(),
            real("RESI_GLOB_RELA")
                .doc("residual relative to external forces, reactions and inertia; 1e-6 when no criterion is given")
                .kw(),
            real("RESI_COMP_RELA")
                .doc("residual relative by component (forbidden in dynamics)")
                .kw(),
            int("ITER_GLOB_MAXI")
                .default(i(10))
                .min_val(0.0)
                .doc("maximum Newton iterations per step (0 acts as 1: the prediction only)")
                .kw(),
            int("ITER_GLOB_ELAS").default(i(25)).kw(),
            oui_non("ARRET", "OUI")
                .doc("'NON' accepts a step not converged at ITER_GLOB_MAXI, with an alarm")
                .kw(),
        ],
    )
    .defaulted()
    .rules(vec![present_absent(
        "RESI_REFE_RELA",
        &["RESI_GLOB_MAXI", "RESI_GLOB_RELA", "RESI_COMP_RELA"],
    )])
    .doc("Newton convergence criteria; all criteria given must hold")
    .kw()
}

/// The singularity test of `SOLVEUR` (NPREC, STOP_SINGULIER, read as the
/// chosen METHODE reads them; code_aster's defaults without SOLVEUR).
pub fn singularity_check(args: &crate::commands::Args) -> crate::solver::SingularityCheck {
    let Some(o) = args.fact("SOLVEUR") else {
        return Default::default();
    };
    crate::solver::SingularityCheck::from_solveur(
        o.text("METHODE").unwrap_or("MUMPS"),
        o.int("NPREC").unwrap_or(8),
        o.text("STOP_SINGULIER").unwrap_or("OUI") == "OUI",
    )
}

/// The .mess note of a given `SOLVEUR`.
pub const SOLVEUR_NOTE: &str = "SOLVEUR: every METHODE maps to one sparse direct solver (faer: Cholesky for a symmetric matrix, LU otherwise); NPREC and STOP_SINGULIER are honoured (a pivot that lost NPREC decimals against its diagonal entry is singular), the other settings are accepted and ignored";

/// `SOLVEUR` (`C_SOLVEUR`, nonlinear commands): the linear solver.
pub fn c_solveur() -> Keyword {
    let npred = || int("NPREC").default(i(8)).kw();
    let stop = || {
        oui_non("STOP_SINGULIER", "OUI")
            .doc("stop on a singular matrix")
            .kw()
    };
    let elim = || oui_non("ELIM_LAGR", "NON").kw();
    fact(
        "SOLVEUR",
        vec![
            text("METHODE")
                .into(&["MULT_FRONT", "LDLT", "MUMPS", "GCPC", "PETSC"])
                .default(t("MUMPS"))
                .doc("linear solver; any direct solver gives the same physics")
                .kw(),
            block(
                "b_mult_front",
                eq("METHODE", "MULT_FRONT"),
                vec![
                    text("RENUM")
                        .into(&["MD", "MDA", "METIS"])
                        .default(t("METIS"))
                        .kw(),
                    npred(),
                    elim(),
                    stop(),
                ],
            )
            .kw(),
            block(
                "b_ldlt",
                eq("METHODE", "LDLT"),
                vec![
                    text("RENUM").into(&["RCMK"]).default(t("RCMK")).kw(),
                    npred(),
                    elim(),
                    stop(),
                ],
            )
            .kw(),
            block(
                "b_mumps",
                eq("METHODE", "MUMPS"),
                vec![
                    text("RENUM")
                        .into(&[
                            "AMD", "AMF", "PORD", "METIS", "QAMD", "SCOTCH", "AUTO", "PARMETIS",
                            "PTSCOTCH",
                        ])
                        .default(t("AUTO"))
                        .kw(),
                    npred(),
                    text("ELIM_LAGR")
                        .into(&["OUI", "NON", "LAGR2"])
                        .default(t("LAGR2"))
                        .kw(),
                    stop(),
                    text("TYPE_RESOL")
                        .into(&["NONSYM", "SYMGEN", "SYMDEF", "AUTO"])
                        .default(t("AUTO"))
                        .kw(),
                    text("ACCELERATION")
                        .into(&["AUTO", "FR", "FR+", "LR", "LR+"])
                        .default(t("AUTO"))
                        .kw(),
                    real("LOW_RANK_SEUIL").default(r(0.0)).kw(),
                    text("PRETRAITEMENTS")
                        .into(&["SANS", "AUTO"])
                        .default(t("AUTO"))
                        .kw(),
                    text("POSTTRAITEMENTS")
                        .into(&["SANS", "AUTO", "FORCE", "MINI"])
                        .default(t("AUTO"))
                        .kw(),
                    int("PCENT_PIVOT").default(i(20)).min_val(1.0).kw(),
                    real("RESI_RELA")
                        .default(r(-1.0))
                        .doc("residual check of each solve (negative: none)")
                        .kw(),
                    text("GESTION_MEMOIRE")
                        .into(&["IN_CORE", "OUT_OF_CORE", "AUTO", "EVAL"])
                        .default(t("AUTO"))
                        .kw(),
                    real("FILTRAGE_MATRICE").default(r(-1.0)).kw(),
                    oui_non("MIXER_PRECISION", "NON").kw(),
                    oui_non("MATR_DISTRIBUEE", "NON").kw(),
                ],
            )
            .kw(),
            block(
                "b_gcpc",
                eq("METHODE", "GCPC"),
                vec![
                    text("PRE_COND")
                        .into(&["LDLT_INC", "LDLT_SP"])
                        .default(t("LDLT_INC"))
                        .kw(),
                    real("RESI_RELA").default(r(1e-6)).kw(),
                    int("NMAX_ITER").default(i(0)).kw(),
                    elim(),
                ],
            )
            .kw(),
            block(
                "b_petsc",
                eq("METHODE", "PETSC"),
                vec![
                    text("ALGORITHME")
                        .into(&["CG", "CR", "GMRES", "GCR", "FGMRES", "GMRES_LMP"])
                        .default(t("FGMRES"))
                        .kw(),
                    text("PRE_COND")
                        .into(&[
                            "LDLT_INC",
                            "LDLT_SP",
                            "JACOBI",
                            "SOR",
                            "ML",
                            "BOOMER",
                            "GAMG",
                            "BLOC_LAGR",
                            "FIELDSPLIT",
                            "SANS",
                        ])
                        .default(t("LDLT_SP"))
                        .kw(),
                    real("RESI_RELA").default(r(1e-6)).kw(),
                    int("NMAX_ITER").default(i(0)).kw(),
                    elim(),
                    oui_non("MATR_DISTRIBUEE", "NON").kw(),
                ],
            )
            .kw(),
        ],
    )
    .defaulted()
    .doc("linear solver (SOLVEUR=_F() means all defaults)")
    .kw()
}

/// `RECH_LINEAIRE` (`C_RECH_LINEAIRE`): line search on the Newton update.
pub fn c_rech_lineaire() -> Keyword {
    fact(
        "RECH_LINEAIRE",
        vec![
            text("METHODE")
                .into(&["CORDE", "MIXTE", "PILOTAGE"])
                .default(t("CORDE"))
                .kw(),
            real("RESI_LINE_RELA").default(r(1e-1)).kw(),
            int("ITER_LINE_MAXI").default(i(3)).max_val(1000.0).kw(),
            real("RHO_MIN").default(r(1e-2)).kw(),
            real("RHO_MAX").default(r(1e1)).kw(),
            real("RHO_EXCL").default(r(9e-3)).min_val(0.0).kw(),
        ],
    )
    .doc("line search (code_aster: forbidden with continuous contact, an alarm with discrete contact); not implemented yet in STAT_NON_LINE and implicit DYNA_NON_LINE (a located error at the run), accepted without effect by an explicit scheme as code_aster")
    .kw()
}

/// `RESULTAT` of STAT_NON_LINE and DYNA_NON_LINE: code_aster ≥ 15 names
/// the result a call continues in place there (`reentrant="f:RESULTAT"`:
/// `R = DYNA_NON_LINE(reuse=R, RESULTAT=R, ...)`); the checker requires it
/// to be the reused concept.
pub fn c_resultat_reuse() -> Keyword {
    concept("RESULTAT", &[C::EvolNoli])
        .doc("the result continued in place, the same as reuse= (code_aster 15 and later write reuse=R, RESULTAT=R); the initial state is still ETAT_INIT's")
        .kw()
}

/// `ETAT_INIT` (`C_ETAT_INIT` for DYNA_NON_LINE).
pub fn c_etat_init() -> Keyword {
    etat_init_with(true)
}

/// `ETAT_INIT` of STAT_NON_LINE: no VITE or ACCE.
pub fn c_etat_init_stat() -> Keyword {
    etat_init_with(false)
}

fn etat_init_with(motion: bool) -> Keyword {
    let mut kws = vec![
        concept("DEPL", &[C::ChamNo])
            .doc("initial displacement field")
            .kw(),
        concept("SIGM", &[C::ChamElem, C::Carte])
            .doc("initial stresses at the Gauss points (CREA_CHAMP ELGA_SIEF_R, AFFE or EXTR of a SIEF_ELGA; or CART_SIEF_R, a value per cell given to each of its points); a component not given is 0; with EVOL_NOLI, replaces its stresses")
            .kw(),
        concept("VARI", &[C::ChamElem])
            .doc("initial internal variables at the Gauss points (CREA_CHAMP ELGA_VARI_R); the count of each element's law is checked; with EVOL_NOLI, replaces its variables")
            .kw(),
    ];
    if motion {
        kws.push(
            concept("VITE", &[C::ChamNo])
                .doc("initial velocity field")
                .kw(),
        );
        kws.push(
            concept("ACCE", &[C::ChamNo])
                .doc("initial acceleration; absent: solved from M a0 = F_ext - F_int")
                .kw(),
        );
    }
    kws.extend([
        concept("EVOL_NOLI", &[C::EvolNoli])
            .doc(
                "continue from a stored state of this result (the last one unless INST/NUME_ORDRE)",
            )
            .kw(),
        int("NUME_ORDRE")
            .doc("index of the stored state to start from")
            .kw(),
        real("INST")
            .doc("instant of the stored state to start from")
            .kw(),
        int("NUME_DIDI")
            .not_built_any("no TYPE_CHARGE='DIDI' load")
            .kw(),
        real("INST_ETAT_INIT")
            .doc("overrides the initial instant taken from EVOL_NOLI")
            .kw(),
    ]);
    kws.extend(critere_precision(1e-6));
    let one_of: &[&'static str] = if motion {
        &["EVOL_NOLI", "ACCE", "VITE", "DEPL", "SIGM", "VARI"]
    } else {
        &["EVOL_NOLI", "DEPL", "SIGM", "VARI"]
    };
    fact("ETAT_INIT", kws)
        .rules(vec![au_moins_un(one_of), exclus(&["NUME_ORDRE", "INST"])])
        .doc("initial state (absent fields are zero); compulsory with reuse= (checked when run)")
        .kw()
}

/// `INCREMENT` (`C_INCREMENT('MECANIQUE')`).
pub fn c_increment() -> Keyword {
    fact(
        "INCREMENT",
        vec![
            concept("LIST_INST", &[C::Listr8, C::ListInst])
                .required()
                .doc("time list: a plain DEFI_LIST_REEL list (no step cutting) or a DEFI_LIST_INST")
                .kw(),
            int("NUME_INST_INIT").kw(),
            real("INST_INIT")
                .doc("first instant; absent: from ETAT_INIT or the list's first value")
                .kw(),
            int("NUME_INST_FIN").kw(),
            real("INST_FIN")
                .doc("last instant, must be in the list; absent: the list's last value")
                .kw(),
            real("PRECISION")
                .default(r(1e-6))
                .doc("instant search tolerance, times the smallest step of the list (absolute)")
                .kw(),
        ],
    )
    .required()
    .rules(vec![
        exclus(&["NUME_INST_INIT", "INST_INIT"]),
        exclus(&["NUME_INST_FIN", "INST_FIN"]),
    ])
    .doc("time stepping")
    .kw()
}

/// ENERGIE of STAT/DYNA_NON_LINE: the energy balance table.
pub fn c_energie() -> Keyword {
    fact(
        "ENERGIE",
        vec![text("CALCUL").into(&["OUI"]).default(t("OUI")).kw()],
    )
    .doc("energy balance table")
    .kw()
}

/// `ARCHIVAGE` (`C_ARCHIVAGE`).
pub fn c_archivage() -> Keyword {
    let mut kws = vec![
        concept("LIST_INST", &[C::Listr8])
            .doc("archive the steps at these instants")
            .kw(),
        real("INST")
            .many()
            .doc("archive the steps at these instants")
            .kw(),
        int("PAS_ARCH").doc("archive every PAS_ARCH steps").kw(),
    ];
    kws.extend(critere_precision(1e-6));
    kws.push(
        text("CHAM_EXCLU")
            .many()
            .doc("fields left out of every archived instant but the last one of the call (which keeps them all, as code_aster forces it)")
            .kw(),
    );
    fact("ARCHIVAGE", kws)
        .defaulted()
        .rules(vec![exclus(&["PAS_ARCH", "LIST_INST", "INST"])])
        .doc("which steps are stored; default every step; the initial and last states are always stored")
        .kw()
}

/// `SUIVI_DDL` (`C_SUIVI_DDL`): extra columns of the convergence table.
///
/// Deviation: code_aster declares `TOUT` with default 'OUI' together with
/// UN_PARMI(TOUT, GROUP_MA, ...); here `TOUT` is optional under EXCLUS and
/// giving no location means the whole model, which is the same thing.
pub fn c_suivi_ddl() -> Keyword {
    let mut kws = monitored_keywords();
    kws.push(text("TITRE").count(1, 3).kw());
    fact("SUIVI_DDL", kws)
        .max(4)
        .doc("up to 4 monitored quantities printed in the Newton table; no effect on results")
        .kw()
}

/// `OBSERVATION` (`C_OBSERVATION`): SUIVI_DDL's selection written to the
/// result's table 'OBSERVATION' at chosen instants.
pub fn c_observation() -> Keyword {
    let mut kws = monitored_keywords();
    kws.extend([
        text("TITRE")
            .doc("NOM_OBSERVATION of the rows; absent: OBSERVATION_<occurrence>")
            .kw(),
        oui_non("OBSE_ETAT_INIT", "OUI")
            .doc("observe the initial state too")
            .kw(),
        concept("LIST_INST", &[C::Listr8])
            .doc("observe the steps at these instants")
            .kw(),
        real("INST")
            .many()
            .doc("observe the steps at these instants")
            .kw(),
        int("PAS_OBSE")
            .doc("observe every PAS_OBSE computed steps")
            .kw(),
    ]);
    kws.extend(critere_precision(1e-6));
    fact("OBSERVATION", kws)
        .many()
        .max(99)
        .rules(vec![exclus(&["PAS_OBSE", "LIST_INST", "INST"])])
        .doc("values written to the result's table 'OBSERVATION' (RECU_TABLE) at the chosen instants; absent LIST_INST, INST and PAS_OBSE: every computed step")
        .kw()
}

/// The selection shared by SUIVI_DDL and OBSERVATION.
fn monitored_keywords() -> Vec<Keyword> {
    let nodal = ["DEPL", "VITE", "ACCE", "FORC_NODA"];
    let elga = ["SIEF_ELGA", "VARI_ELGA", "EPSI_ELGA"];
    vec![
        text("NOM_CHAM")
            .required()
            .into(&[
                "DEPL",
                "VITE",
                "ACCE",
                "FORC_NODA",
                "SIEF_ELGA",
                "VARI_ELGA",
                "EPSI_ELGA",
            ])
            .kw(),
        text("EVAL_CHAM")
            .into(&["MIN", "MAX", "MOY", "MAXI_ABS", "MINI_ABS", "VALE"])
            .default(t("VALE"))
            .doc("reduction over the selected nodes or cells")
            .kw(),
        text("NOM_CMP")
            .required()
            .count(1, 20)
            .doc("components, e.g. 'V1' for the first internal variable")
            .kw(),
        text("EVAL_CMP")
            .into(&["VALE"])
            .default(t("VALE"))
            .doc("'FORMULE' of code_aster is not supported")
            .kw(),
        block(
            "b_cham_no",
            is_in("NOM_CHAM", &nodal),
            vec![tout(), noeud(), group_no(), maille(), group_ma()],
        )
        .rules(vec![exclus(&[
            "NOEUD", "GROUP_NO", "GROUP_MA", "MAILLE", "TOUT",
        ])])
        .kw(),
        block(
            "b_cham_elga",
            is_in("NOM_CHAM", &elga),
            vec![
                tout(),
                maille(),
                group_ma(),
                text("EVAL_ELGA")
                    .into(&["MIN", "MAX", "VALE"])
                    .default(t("VALE"))
                    .doc("reduction over the Gauss points of a cell")
                    .kw(),
                block(
                    "b_elga_vale",
                    eq("EVAL_ELGA", "VALE"),
                    vec![
                        int("POINT").required().many().kw(),
                        int("SOUS_POINT").many().kw(),
                    ],
                )
                .kw(),
            ],
        )
        .rules(vec![exclus(&["GROUP_MA", "MAILLE", "TOUT"])])
        .kw(),
    ]
}

/// `AFFICHAGE` (`C_AFFICHAGE`): layout of the convergence table.
pub fn c_affichage() -> Keyword {
    fact(
        "AFFICHAGE",
        vec![
            oui_non("INFO_RESIDU", "NON")
                .doc("print where the largest residual is")
                .kw(),
            oui_non("INFO_TEMPS", "NON").kw(),
            int("UNITE").doc("also write the table to this unit").kw(),
            int("PAS").doc("print every PAS steps").kw(),
        ],
    )
    .doc("convergence table layout")
    .kw()
}

// ---------------------------------------------------------------------------
// Tables.

/// `FILTRE` of table commands: rows kept when all filters hold.
pub fn c_filtre() -> Keyword {
    fact(
        "FILTRE",
        vec![
            text("NOM_PARA").required().doc("column filtered on").kw(),
            text("CRIT_COMP")
                .into(&[
                    "EQ", "LT", "GT", "NE", "LE", "GE", "VIDE", "NON_VIDE", "MAXI", "MAXI_ABS",
                    "MINI", "MINI_ABS",
                ])
                .default(t("EQ"))
                .doc("comparison; MAXI/MINI... keep the first row holding the extreme value")
                .kw(),
            block(
                "b_vale",
                is_in("CRIT_COMP", &["EQ", "NE", "GT", "LT", "GE", "LE"]),
                vec![
                    real("VALE").doc("value, for real columns").kw(),
                    int("VALE_I")
                        .doc("value, for integer columns such as NUME_ORDRE")
                        .kw(),
                    text("VALE_K").doc("value, for text columns").kw(),
                ],
            )
            .rules(vec![un_parmi(&["VALE", "VALE_I", "VALE_K"])])
            .kw(),
            text("CRITERE")
                .into(&["RELATIF", "ABSOLU"])
                .default(t("RELATIF"))
                .kw(),
            real("PRECISION")
                .default(r(1e-3))
                .doc("tolerance of EQ/NE on reals")
                .kw(),
        ],
    )
    .many()
    .doc("row filters, all applied")
    .kw()
}

/// The test keywords of TEST_RESU and TEST_TABLE (`C_TEST_REFERENCE`).
///
/// `multi` is code_aster's `multi_prec` (TEST_RESU/RESU): TOLE_MACHINE and
/// CRITERE then take two values, the second for the instant search.
/// `with_text` adds the string variants (tables). Returns the keywords
/// and the rules to add to the enclosing level.
///
/// Deliberate deviation: `VALE_CALC` is optional in aster (code_aster makes
/// one of VALE_CALC* compulsory) so that a new study can run once before
/// its non-regression values are recorded; the report then prints a SKIP
/// line for the non-regression check.
pub fn c_test_reference(multi: bool, with_text: bool) -> (Vec<Keyword>, Vec<Rule>) {
    let mut calc = vec!["VALE_CALC", "VALE_CALC_I"];
    let mut refe = vec!["VALE_REFE", "VALE_REFE_I"];
    let mut kws = vec![
        real("VALE_CALC")
            .many()
            .doc("value computed by the reference run (non-regression); OPTIONAL in aster, unlike code_aster: when absent the non-regression check is SKIPped")
            .kw(),
        int("VALE_CALC_I")
            .many()
            .doc("integer VALE_CALC (optional in aster, see VALE_CALC)")
            .kw(),
    ];
    if with_text {
        kws.push(
            text("VALE_CALC_K")
                .many()
                .doc("text VALE_CALC (optional in aster, see VALE_CALC)")
                .kw(),
        );
        calc.push("VALE_CALC_K");
        refe.push("VALE_REFE_K");
    }
    kws.push(
        real("ORDRE_GRANDEUR")
            .doc("magnitude used for ABSOLU tests; lets VALE_CALC=0 be tested instead of skipped")
            .kw(),
    );
    kws.push(text("LEGENDE").doc("label printed in the report").kw());
    kws.push(
        oui_non("VALE_ABS", "NON")
            .doc("compare absolute values")
            .kw(),
    );
    kws.push(
        text("TYPE_TEST")
            .into(&["SOMM_ABS", "SOMM", "MAX", "MIN"])
            .doc("test an aggregate over the field or column instead of one value")
            .kw(),
    );
    if multi {
        kws.push(
            real("TOLE_MACHINE")
                .count(1, 2)
                .doc("non-regression tolerance, then instant-search tolerance; both 1e-6 when absent")
                .kw(),
        );
        kws.push(
            text("CRITERE")
                .count(1, 2)
                .into(&["RELATIF", "ABSOLU"])
                .doc("test criterion, then instant-search criterion; both 'RELATIF' when absent")
                .kw(),
        );
    } else {
        kws.push(
            real("TOLE_MACHINE")
                .default(r(1e-6))
                .doc("non-regression tolerance")
                .kw(),
        );
        kws.push(
            text("CRITERE")
                .into(&["RELATIF", "ABSOLU"])
                .default(t("RELATIF"))
                .doc("relative or absolute comparison")
                .kw(),
        );
    }
    kws.push(
        text("REFERENCE")
            .into(&["ANALYTIQUE", "SOURCE_EXTERNE", "AUTRE_ASTER", "NON_DEFINI"])
            .doc("origin of VALE_REFE; adds a second check labelled with it")
            .kw(),
    );
    let mut ref_kws = vec![
        real("VALE_REFE").many().doc("reference value").kw(),
        int("VALE_REFE_I").many().kw(),
    ];
    if with_text {
        ref_kws.push(text("VALE_REFE_K").many().kw());
    }
    ref_kws.push(
        real("PRECISION")
            .default(r(1e-3))
            .doc("tolerance of the reference check")
            .kw(),
    );
    kws.push(
        block("b_reference", present("REFERENCE"), ref_kws)
            .rules(vec![Rule::ExactlyOne(refe)])
            .kw(),
    );
    (kws, vec![Rule::Exclusive(calc)])
}

/// Where a DDL_IMPO applies: TOUT, GROUP_MA, MAILLE, GROUP_NO, NOEUD and
/// the SANS_* exclusions (AFFE_CHAR_MECA and AFFE_CHAR_MECA_F).
/// An imposed-dof factor keyword (DDL_IMPO, MECA_IMPO): the selection
/// `kws` with one value keyword per component, repeatable, needing a
/// location and one of `components`.
pub fn imposed_dofs(
    name: &'static str,
    kws: Vec<Keyword>,
    components: &[&'static str],
    doc: &'static str,
) -> Factor {
    fact(name, kws)
        .many()
        .rules(vec![
            au_moins_un(&["TOUT", "GROUP_MA", "MAILLE", "GROUP_NO", "NOEUD"]),
            au_moins_un(components),
        ])
        .doc(doc)
}

pub fn ddl_selection() -> Vec<Keyword> {
    vec![
        tout(),
        group_ma(),
        maille(),
        group_no(),
        noeud(),
        text("SANS_GROUP_MA").many().kw(),
        text("SANS_MAILLE").many().hidden().kw(),
        text("SANS_GROUP_NO")
            .many()
            .doc("nodes excluded from the selection")
            .kw(),
        text("SANS_NOEUD").many().hidden().kw(),
    ]
}
