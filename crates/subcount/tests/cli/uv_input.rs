//! Texture coordinates in the input: a `vt` index out of range is refused with exit 3,
//! naming the file, the line and the corner, by every command that reads the mesh.

use crate::util::{data, fails};

#[test]
fn a_texture_coordinate_index_out_of_range_is_exit_3_naming_file_line_and_corner() {
    let path = data("bad_vt_index_range.obj");
    let message = "bad_vt_index_range.obj: line 11: corner 3: texture coordinate index 5 is out of range (the file has 4 texture coordinates)";
    for command in [
        &["stats"][..],
        &["verify", "--scheme", "catmull-clark", "--levels", "1"],
        &["subdivide", "--scheme", "catmull-clark", "--levels", "1"],
        &["table", "--scheme", "catmull-clark"],
    ] {
        let mut args: Vec<&str> = command.to_vec();
        args.extend(["--mesh", &path]);
        fails(&args, 3, message);
    }
}
