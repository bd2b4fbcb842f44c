// The seed scene (assets/scenes/seed.toml) in POV-Ray's language: the same objects,
// materials, light and camera, for `prism bench speed` to race POV-Ray 3.7 on
// (docs/benchmarks/speed.md). Its right vector of -x turns POV-Ray's left-handed
// coordinates into prism's; max_trace_level counts the primary ray, so 6 is prism's
// max_depth of 5. Run beside earth.jpg:
//   povray +Iseed.pov +W800 +H600 +A0.0 +AM1 +R4 +WT2 -D File_Gamma=1.0
#version 3.7;
global_settings { assumed_gamma 1.0 ambient_light 1 max_trace_level 6 }
#declare Aspect = 800 / 600;
camera { perspective location <0, 0, 0> look_at <0, 0, -1> right -x * Aspect up y
  angle 2 * degrees(atan(tan(radians(28.072487 / 2)) * Aspect)) }
background { rgb 0 }
light_source { <10, 40, -3> rgb 1 }
#declare Shiny = finish { ambient 0.2 diffuse 1 phong 1 phong_size 50 };
polygon { 5, <-40, -15, -40>, <40, -15, -40>, <40, -15, -200>, <-40, -15, -200>, <-40, -15, -40>
  pigment { checker rgb <0.92, 0.88, 0.78> rgb <0.22, 0.24, 0.30> scale 5 }
  finish { ambient 0.2 diffuse 1 } }
sphere { <-5, 0, -100>, 14 pigment { rgb <0, 0, 1> } finish { Shiny reflection 0.8 } }
sphere { <0, 0, 0>, 5
  pigment { image_map { jpeg "earth.jpg" map_type 1 } }
  finish { ambient 0.2 diffuse 1 phong 0.3 phong_size 30 } translate <10, 7, -80> }
sphere { <9, -10, -60>, 4 pigment { rgbt <0.75, 0.85, 1.0, 0.9> }
  finish { Shiny phong_size 100 reflection 0.1 } interior { ior 1.43 } }
sphere { <14, 9, -62>, 3 pigment { rgbt <0.75, 0.85, 1.0, 0.9> }
  finish { Shiny phong_size 100 reflection 0.1 } interior { ior 1.002 } }
sphere { <-9, -10, -60>, 3.5 pigment { rgbt <0, 1, 0, 0.9> } finish { Shiny } }
cylinder { <-14, -15, -75>, <-14, -6, -75>, 3
  pigment { gradient x color_map { [0.5 rgb <0, 1, 0.2>] [0.5 rgb <0.1, 0, 1>] } scale 3 }
  finish { ambient 0.2 diffuse 1 phong 0.6 phong_size 40 } }
mesh {
  #declare A = <2, -15, -64.381198>; #declare B = <6, -15, -71.309401>;
  #declare C = <-2, -15, -71.309401>; #declare D = <2, -8.468037, -69>;
  triangle { A, B, C } triangle { A, B, D } triangle { B, C, D } triangle { C, A, D }
  pigment { checker rgb <0, 1, 0> rgb <1, 1, 0> scale 1.5 }
  finish { ambient 0.2 diffuse 1 phong 0.6 phong_size 40 } }
