//! Factor blocks shared by several commands (code_aster's `Cata/Commons`).
