O1002 (spec L5185-5209: the electric tailstock B at 300 rpm by P11, to torque mode at 50 % by P10 as O9030 of M78, back to position mode with a 50 % torque limit by P12 as O9031 of M79, then away by G160 at that limit)
G98 G00 X0 Z10
G10 L14 P11 B300
G10 L14 P10 B50
G04 X2
G10 L14 P12 B50
G160 P50 UB100 F500
M30
