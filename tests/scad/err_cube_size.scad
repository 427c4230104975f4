// A cube whose size is a string is refused, not built as a unit cube.
// expect error: cube(): size must be a number or [x, y, z]
// expect no-openscad: OpenSCAD warns and builds a unit cube
cube("a");
