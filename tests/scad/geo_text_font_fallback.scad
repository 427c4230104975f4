// text() with a font that is not installed: fontconfig substitutes another (as it does
// for OpenSCAD), and cellforge says so in a warning naming the font it chose.
// expect warning: text(): font "No Such Font Xyz" is not installed; fontconfig chose
// expect valid
// expect counts: volumes=1
linear_extrude(1) text("l", font = "No Such Font Xyz");
