// import(layer = ...) reads one layer; origin and scale map points to (p - origin) *
// scale: the triangle of legs 4 and 3 at (20, 0), scaled by 2 about (20, 0).
// expect volume: 24
// expect bbox: [0, 0, 0] [8, 6, 1]
linear_extrude(1) import(file = "data/plate.dxf", layer = "tri", origin = [20, 0], scale = 2);
