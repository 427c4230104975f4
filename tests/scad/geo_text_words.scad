// text() with curves, holes and kerning: a string in two fonts that Debian ships
// (fonts-liberation, fonts-dejavu-core), named so that cellforge and OpenSCAD use the
// same files. scripts/openscad_compare.sh checks its volume and box against OpenSCAD's;
// here: a valid solid, one volume per piece of ink ("Hello," 6, "B8%&" 6: the % is three).
// expect valid
// expect counts: volumes=12
linear_extrude(2) text("Hello,", size = 8, font = "Liberation Sans:style=Bold", $fn = 32);
translate([0, -15, 0])
  linear_extrude(1) text("B8%&", size = 9, font = "DejaVu Sans", halign = "right");
