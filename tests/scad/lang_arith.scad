// Arithmetic and precedence: ^ binds tighter than unary minus, * before +.
// expect echo: ECHO: 7, 1024, 1, -4, 9, 2.5
echo(1 + 2 * 3, 2 ^ 10, 7 % 3, -2 ^ 2, (1 + 2) * 3, 5 / 2);
