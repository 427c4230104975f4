// Trigonometry in degrees (exact at multiples of 30 and 45), and the rest of the math.
// expect echo: ECHO: 0.5, 0.5, 1, 45, 4, 1.41421, 3, -1, -2, 2, 3, 1, 0, 3
echo(sin(30), cos(60), tan(45), atan2(1, 1), sqrt(16), pow(2, 0.5), abs(-3), sign(-2),
     floor(-1.5), ceil(1.2), round(2.5), exp(0), ln(1), log(1000));
