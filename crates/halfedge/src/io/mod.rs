//! Reading and writing meshes (OBJ, OFF).
