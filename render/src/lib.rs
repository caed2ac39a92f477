//! Rasterise and write plain 2-D geometry.
