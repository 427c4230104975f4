// expect volume: 4
linear_extrude(1) projection() cube(2);
