O1000 (gsk A.6.4: the arc through three points, relative and absolute middle point)
G00 X18 Z50
G05 X58 Z30 I4 K-12 F30
X18 Z50 I-16 K8
G05.1 X58 Z30 I26 K38
G01 X60
M30
