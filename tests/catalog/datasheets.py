"""Datasheet texts the tests share."""

NU206_AS_MINE = """
[[bearing]]
designation = "MY NU206"   # the catalogue's NU 206 ECP (SKF GC 6000, pp. 524-525), renamed
d_mm = 30
D_mm = 62
B_mm = 16
Z = 12
Dw_mm = 9.0
Lwe_mm = 9.52
dm_mm = 46.5
Pd_um = 32.5
C_kN = 44
C0_kN = 36.5
Pu_kN = 4.55
ref_speed_rpm = 13000
lim_speed_rpm = 14000
explorer = 1
"""
"""A roller bearing of a user's datasheet: NU 206's numbers under its own designation."""
