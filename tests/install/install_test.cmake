# The installed package used the way a game uses it: installs the build tree into a
# temporary prefix, builds examples/game_layer against it with find_package, runs it,
# and compiles and runs a small program with the flags of the pkg-config file.
#
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DCXX=... -DBUILD_TYPE=...
#         [-DEXTRA_FLAGS=...] -P install_test.cmake
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR CXX BUILD_TYPE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_test.cmake: -D${var}=... is required")
  endif()
endforeach()

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}):\n${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

run("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(file include/cyclone/body.h include/cyclone/world.h include/cyclone/world/world.h)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "install did not install ${file}")
  endif()
endforeach()
file(GLOB_RECURSE config ${prefix}/*/cycloneConfig.cmake)
file(GLOB_RECURSE version ${prefix}/*/cycloneConfigVersion.cmake)
file(GLOB_RECURSE pc ${prefix}/*/pkgconfig/cyclone.pc)
if(NOT config OR NOT version OR NOT pc)
  message(FATAL_ERROR "install lacks the package files: config '${config}' version '${version}' pc '${pc}'")
endif()

# find_package: the example is its own project and sees only the prefix.
set(game ${WORK_DIR}/game_layer)
run("configuring game_layer" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/game_layer -B ${game}
  -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
  -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=${BUILD_TYPE}
  "-DCMAKE_CXX_FLAGS=${EXTRA_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${EXTRA_FLAGS}")
file(STRINGS ${game}/CMakeCache.txt found REGEX "^cyclone_DIR:")
string(FIND "${found}" "${prefix}/" at)
if(NOT at GREATER -1)
  message(FATAL_ERROR "game_layer found cyclone elsewhere than the prefix: ${found}")
endif()
run("building game_layer" ${CMAKE_COMMAND} --build ${game})
run("running game_layer" ${game}/game_layer)
message(STATUS "game_layer:\n${last_output}")

# pkg-config: the flags a Makefile-built game would use.
find_program(PKG_CONFIG pkg-config)
if(PKG_CONFIG)
  get_filename_component(pc_dir ${pc} DIRECTORY)
  set(ENV{PKG_CONFIG_PATH} ${pc_dir})
  run("pkg-config" ${PKG_CONFIG} --cflags --libs cyclone)
  string(STRIP "${last_output}" flags)
  separate_arguments(flags UNIX_COMMAND "${flags}")
  separate_arguments(extra UNIX_COMMAND "${EXTRA_FLAGS}")
  file(WRITE ${WORK_DIR}/hello.cpp [=[
#include <cyclone/world.h>
int main() {
    cyclone::World world;
    cyclone::BodySettings ball;
    ball.shape = cyclone::Shape::sphere(0.5);
    const cyclone::BodyId id = world.addBody(ball);
    world.step(0.5);
    // Free fall, one semi-implicit step of 0.5 s in 4 sub-steps of 0.125 s:
    // y = -g h^2 (1 + 2 + 3 + 4) = -9.81 * 0.015625 * 10 = -1.5328125 m.
    const double y = world.body(id).getPosition().y();
    return y < -1.532 && y > -1.534 ? 0 : 1;
}
]=])
  run("compiling with pkg-config flags" ${CXX} -std=c++17 ${extra} ${WORK_DIR}/hello.cpp -o ${WORK_DIR}/hello ${flags})
  run("running the pkg-config build" ${WORK_DIR}/hello)
endif()
file(REMOVE_RECURSE ${WORK_DIR})
