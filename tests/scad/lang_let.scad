// let() binds in order; each binding sees the ones before it.
// expect echo: ECHO: 8, [1, 3]
echo(let(a = 2, b = a * 3) a + b, let(p = 1) [p, p + 2]);
