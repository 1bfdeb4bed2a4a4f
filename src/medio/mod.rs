//! MED files (HDF5) in and out.
