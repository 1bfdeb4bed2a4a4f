//! Post-processing: tables, the TEST_RESU/TEST_TABLE report, printed results.

pub mod calc_fonction;
pub mod calc_table;
pub mod formula;
pub mod function;
pub mod post_elem;
pub mod table;
pub mod test_report;
