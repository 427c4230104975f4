// text(direction = "ttb"): glyphs stacked downwards (HarfBuzz's vertical advances),
// centred on the widest; language and script given. Compared with OpenSCAD.
// expect valid
// expect counts: volumes=3
linear_extrude(1)
  text("IOU", size = 5, font = "DejaVu Sans", direction = "ttb", language = "en",
       script = "latin", valign = "top", halign = "center");
