// Vector arithmetic: element-wise sums, scaling, dot and matrix products.
// expect echo: ECHO: [4, 6], [2, 4, 6], 11, [3, 7], [4, 6], [2], [-1, -2]
echo([1, 2] + [3, 4], [1, 2, 3] * 2, [1, 2] * [3, 4], [[1, 2], [3, 4]] * [1, 1],
     [1, 1] * [[1, 2], [3, 4]], [1, 2] + [1], -[1, 2]);
