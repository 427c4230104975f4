// A syntax error names the place.
// expect error: lang_syntax_error.scad:4:8: expected ',' or ')'
// expect no-openscad: a syntax error
cube(1 2);
