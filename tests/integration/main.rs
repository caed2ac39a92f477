//! Integration tests, one module per stage.

mod mesh;
