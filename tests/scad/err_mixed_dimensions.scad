// 2D and 3D objects in one union are refused.
// expect error: a 2D object among 3D ones
// expect no-openscad: OpenSCAD ignores the 2D object with a warning
union() { cube(1); square(1); }
