//! The occupancy index: grown segments, and the clearance test.
