// concat, len, max, min, norm, cross.
// expect echo: ECHO: [1, 2, 3, 4], 3, 4, 1, 5, [0, 0, 1]
echo(concat([1], [2, 3], 4), len([1, 2, 3]), max([3, 1, 4]), min(3, 1, 2), norm([3, 4]),
     cross([1, 0, 0], [0, 1, 0]));
