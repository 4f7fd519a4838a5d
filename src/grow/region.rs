//! The layout region: shapes painted in order on white, white erasing.
