//! Exact word statistics of classic L-systems with big integers.
