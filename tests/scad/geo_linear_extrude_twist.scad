// A twisted square: 2 caps and 4 sides x 4 slices x 2 triangles.
// expect counts: faces=34 vertices=20
// expect valid
linear_extrude(height = 2, twist = 90, slices = 4) square(2, center = true);
