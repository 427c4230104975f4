// polygon() paths that are not one outline with holes: OpenSCAD fills them even-odd.
// Two 2-squares side by side (8), and a 4 x 2 rectangle crossing a 2-square (8 + 4 - 2 * 1).
// expect volume: 18
// expect no-openscad: OpenSCAD 2021 extrudes crossing paths to an open mesh and drops it in a union ("The given mesh is not closed")
linear_extrude(1) polygon(points = [[0, 0], [2, 0], [2, 2], [0, 2], [5, 0], [7, 0], [7, 2], [5, 2]],
                          paths = [[0, 1, 2, 3], [4, 5, 6, 7]]);
translate([0, 10, 0]) linear_extrude(1)
  polygon(points = [[0, 0], [4, 0], [4, 2], [0, 2], [3, 1], [5, 1], [5, 3], [3, 3]],
          paths = [[0, 1, 2, 3], [4, 5, 6, 7]]);
