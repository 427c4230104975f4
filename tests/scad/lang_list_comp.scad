// List comprehensions: for with if, let, and each.
// expect echo: ECHO: [2, 4], [1, 4, 9], [1, 2, 3, 4], [[1, 3], [1, 4], [2, 3], [2, 4]]
echo([for (i = [1:5]) if (i % 2 == 0) i], [for (i = [1:3]) let(s = i * i) s],
     [each [1, 2], each [3:4]], [for (a = [1, 2], b = [3, 4]) [a, b]]);
