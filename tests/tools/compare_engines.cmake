# Runs one scene on both engines through the command-line tools and compares what they write:
# `ricochet sim SCENE --steps N --integrator I --out ours.json --trace 1 --csv trace.csv` and
# `box2d_sim SCENE --steps N --out box2d.json`. Every body's final position must agree within
# TOLERANCE metres and its angle within TOLERANCE radians, and the trace must hold steps 0..N of
# body 1, its last row equal to the final state that --out wrote.
#
# cmake -DRICOCHET=... -DBOX2D_SIM=... -DSCENE=... -DSTEPS=N -DINTEGRATOR=... -DTOLERANCE=...
#       -DWORK=dir -P compare_engines.cmake
foreach(var RICOCHET BOX2D_SIM SCENE STEPS INTEGRATOR TOLERANCE WORK)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "compare_engines: -D${var}=... is required")
  endif()
endforeach()
file(MAKE_DIRECTORY "${WORK}")
execute_process(
  COMMAND "${RICOCHET}" sim "${SCENE}" --steps ${STEPS} --integrator ${INTEGRATOR}
          --out "${WORK}/ours.json" --trace 1 --csv "${WORK}/trace.csv"
  RESULT_VARIABLE ours_rc)
execute_process(COMMAND "${BOX2D_SIM}" "${SCENE}" --steps ${STEPS} --out "${WORK}/box2d.json"
                RESULT_VARIABLE box2d_rc)
if(NOT ours_rc EQUAL 0 OR NOT box2d_rc EQUAL 0)
  message(FATAL_ERROR "compare_engines: ricochet sim exited ${ours_rc}, box2d_sim ${box2d_rc}")
endif()
file(READ "${WORK}/ours.json" ours)
file(READ "${WORK}/box2d.json" box2d)
string(JSON engine GET "${box2d}" engine)
string(JSON count LENGTH "${ours}" bodies)
string(JSON count2 LENGTH "${box2d}" bodies)
if(NOT count EQUAL count2 OR count EQUAL 0)
  message(FATAL_ERROR "compare_engines: ${count} bodies from ricochet, ${count2} from ${engine}")
endif()

# |a - b| <= TOLERANCE compared in micrometres (CMake's math() is integer-only; a micrometre is
# far below any tolerance used here).
function(to_micro value out)
  if(value MATCHES "[eE]([-+]?)0*([0-9]+)$")
    if(CMAKE_MATCH_1 STREQUAL "-" AND CMAKE_MATCH_2 GREATER_EQUAL 7)
      set(value 0)  # below a micrometre, such as 8.3e-09
    else()
      message(FATAL_ERROR "compare_engines: cannot compare ${value} in fixed point")
    endif()
  endif()
  string(REGEX MATCH "^(-?)([0-9]*)\\.?([0-9]*)" _ "${value}")
  set(sign "${CMAKE_MATCH_1}")
  set(int "${CMAKE_MATCH_2}")
  set(frac "${CMAKE_MATCH_3}000000")
  string(SUBSTRING "${frac}" 0 6 frac)
  if(int STREQUAL "")
    set(int 0)
  endif()
  math(EXPR micro "${int} * 1000000 + 1${frac} - 1000000")
  if(sign STREQUAL "-")
    math(EXPR micro "-${micro}")
  endif()
  set(${out} ${micro} PARENT_SCOPE)
endfunction()
to_micro("${TOLERANCE}" tol)

math(EXPR last "${count} - 1")
foreach(i RANGE ${last})
  string(JSON name GET "${ours}" bodies ${i} name)
  foreach(field "position;0" "position;1" "angle")
    string(JSON a GET "${ours}" bodies ${i} ${field})
    string(JSON b GET "${box2d}" bodies ${i} ${field})
    to_micro("${a}" ua)
    to_micro("${b}" ub)
    math(EXPR diff "${ua} - ${ub}")
    if(diff LESS 0)
      math(EXPR diff "-${diff}")
    endif()
    if(diff GREATER tol)
      message(FATAL_ERROR "compare_engines: body ${i} (${name}) ${field}: ricochet ${a}, "
                          "${engine} ${b}, apart by more than ${TOLERANCE}")
    endif()
    message(STATUS "body ${i} (${name}) ${field}: ricochet ${a}, ${engine} ${b}")
  endforeach()
endforeach()

# The trace: a header and steps 0..N of body 1; its last row is the state --out wrote.
file(STRINGS "${WORK}/trace.csv" rows)
list(LENGTH rows n)
math(EXPR expected "${STEPS} + 2")
if(NOT n EQUAL expected)
  message(FATAL_ERROR "compare_engines: trace.csv has ${n} lines, expected ${expected}")
endif()
list(GET rows -1 lastRow)
string(REPLACE "," ";" cells "${lastRow}")
list(GET cells 0 step)
list(GET cells 4 traceY)
string(JSON outY GET "${ours}" bodies 1 position 1)
to_micro("${traceY}" uy)
to_micro("${outY}" uo)
math(EXPR dy "${uy} - ${uo}")
if(NOT step EQUAL STEPS OR dy GREATER 1 OR dy LESS -1)
  message(FATAL_ERROR "compare_engines: the trace ends at step ${step} with y ${traceY}; "
                      "--out wrote y ${outY} after ${STEPS} steps")
endif()
message(STATUS "trace: ${n} lines, last at step ${step}, y ${traceY}")
