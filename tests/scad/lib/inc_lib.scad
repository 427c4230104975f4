// Included by lang_include.scad.
lib_size = 3;
module lib_box() cube(lib_size);
