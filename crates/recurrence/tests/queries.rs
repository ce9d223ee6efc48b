//! Spectrum queries: the dominant eigenvalue.

use crate::util::rec;

#[test]
fn dominant_eigenvalues() {
    assert_eq!(
        rec("[[1,1,1],[0,2,4],[0,0,4]]", "")
            .dominant_eigenvalue()
            .unwrap()
            .to_string(),
        "4"
    );
    assert_eq!(
        rec("[[1,1],[1,0]]", "")
            .dominant_eigenvalue()
            .unwrap()
            .to_string(),
        "1/2+1/2*sqrt(5)"
    );
    assert_eq!(
        rec("[[-3,0],[0,2]]", "")
            .dominant_eigenvalue()
            .unwrap()
            .to_string(),
        "-3"
    );
    assert_eq!(rec("[[0,1],[0,0]]", "").dominant_eigenvalue(), None);
}
