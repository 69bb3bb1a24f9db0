0 BEGIN PGM AXISCAL_CIRCULAR MM
1 ; ISO 230-4 circular test in XY: radius 100 mm about 200, 150
2 ; mm, feed 1000 mm/min, data arc 360 deg from 0 deg, overshoot
3 ; 180 deg, ccw then cw
4 ; written by axiscal: check it on the machine before the test
5 L X+99.000 Y+150.000 R0 FMAX
6 L X+100.000 Y+150.000 R0 F1000
7 ; feed-in arc ccw from 180 deg through 180 deg
8 CC X+200.000 Y+150.000
9 C X+300.000 Y+150.000 DR+ R0 F1000
10 ; data arc ccw from 0 deg through 360 deg
11 C X+100.000 Y+150.000 DR+ R0 F1000
12 C X+300.000 Y+150.000 DR+ R0 F1000
13 ; feed-out arc ccw from 0 deg through 180 deg
14 C X+100.000 Y+150.000 DR+ R0 F1000
15 ; feed-in arc cw from 180 deg through 180 deg
16 C X+300.000 Y+150.000 DR- R0 F1000
17 ; data arc cw from 0 deg through 360 deg
18 C X+100.000 Y+150.000 DR- R0 F1000
19 C X+300.000 Y+150.000 DR- R0 F1000
20 ; feed-out arc cw from 0 deg through 180 deg
21 C X+100.000 Y+150.000 DR- R0 F1000
22 L X+99.000 Y+150.000 R0 F1000
23 L X+99.000 Y+150.000 R0 FMAX M30
24 END PGM AXISCAL_CIRCULAR MM
