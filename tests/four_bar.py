"""A four-bar written here, not shipped: a lubricated finite/Reynolds crank pin (a law given as
a table with parameters) and a torsion spring on the rocker; the model file of the studies and
codec end-to-end tests."""

OMEGA = 209.43951023931953  # [rad/s] the motor's speed in FOUR_BAR (2000 rpm)

FOUR_BAR = """[model]
name = "four-bar (lubricated crank pin, rocker spring)"
gravity = [0.0, -9.81]

[ground.points]
O2 = [0.0, 0.0]
O4 = [0.14, 0.0]

[bodies.crank]
mass = 0.1
inertia = 2.0833e-5
position = [0.025, 0.0]
angle = 0.0
points = { O = [-0.025, 0.0], A = [0.025, 0.0] }

[bodies.coupler]
mass = 0.25
inertia = 4.6875e-4
position = [0.095, 0.06]
angle = 0.9272952180016122
points = { A = [-0.075, 0.0], B = [0.075, 0.0] }

[bodies.rocker]
mass = 0.2
inertia = 2.4e-4
position = [0.14, 0.06]
angle = 1.5707963267948966
points = { O = [-0.06, 0.0], B = [0.06, 0.0] }

[joints.crank_pivot]
type = "revolute"
body_i = "ground"
point_i = "O2"
body_j = "crank"
point_j = "O"

[joints.motor]
type = "angle_driver"
body_i = "ground"
body_j = "crank"
omega = 209.43951023931953

[joints.rocker_pin]
type = "revolute"
body_i = "coupler"
point_i = "B"
body_j = "rocker"
point_j = "B"

[joints.rocker_pivot]
type = "revolute"
body_i = "ground"
point_i = "O4"
body_j = "rocker"
point_j = "O"

[elements.pin]
type = "journal_bearing"
body_i = "coupler"
point_i = "A"
body_j = "crank"
point_j = "A"
bearing_radius = 0.00804
journal_radius = 0.008
length = 0.016
viscosity = 0.05
film = { law = "finite", cavitation = "reynolds" }

[elements.spring]
type = "torsion_spring"
body_i = "ground"
body_j = "rocker"
stiffness = 2.0
damping = 0.001
free_angle = 1.5707963267948966

[simulation]
t_end = 0.03
n_out = 361
solver = "rodas4"
rtol = 1e-7
atol = 1e-10
"""
