//! One compatible morph under a fixed triangulation (docs/design.md §6):
//! every triangle's third vertex moves along a path in its base frame
//! (`paths`, the as-rigid-as-possible guide in `rigid`), and the vertices
//! are laid out along the dual tree from a root (`layout`, `compatible`).

pub(crate) mod compatible;
pub(crate) mod layout;
pub(crate) mod paths;
pub(crate) mod rigid;
