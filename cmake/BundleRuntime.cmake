# CPack pre-build script of the release archive (cmake/Package.cmake, docs/release.md): runs on the staged files
# before they are packed. Copies into lib/ every shared library that the tools and the Python module load, directly
# or through one another, except the ones the target machine brings (the C library family, libstdc++ / libgcc_s,
# the Vulkan loader; cmake/Package.cmake says why), each under the name the binaries ask for (the soname), as a
# plain file. Writes share/doc/sward/bundled-libraries.txt (library, Debian package, version, in name order, with
# the newest glibc and libstdc++ symbol versions anything in the archive needs) and each bundled package's
# copyright file to share/doc/sward/third-party/<package>/copyright. Needs the build machine's dpkg (Debian 12, as
# tools/setup-deps.sh sets up) to name the packages.
cmake_minimum_required(VERSION 3.25)

# The staging folder holds one folder per component (Runtime/, Unspecified/ for the Python module) or the files
# themselves; find the binaries wherever they are.
file(GLOB_RECURSE staged LIST_DIRECTORIES false "${CPACK_TEMPORARY_DIRECTORY}/*")
set(executables)
set(modules)
foreach(file ${staged})
  if(file MATCHES "/bin/sward-[a-z]+$")
    list(APPEND executables ${file})
  elseif(file MATCHES "/python3/dist-packages/sward/_sward[^/]*\\.so$")
    list(APPEND modules ${file})
  endif()
endforeach()
list(FILTER executables INCLUDE REGEX "/bin/sward-render$")
if(NOT executables)
  message(FATAL_ERROR "BundleRuntime: no bin/sward-render under ${CPACK_TEMPORARY_DIRECTORY}")
endif()
get_filename_component(bin_dir ${executables} DIRECTORY)
get_filename_component(root ${bin_dir} DIRECTORY)
file(GLOB executables "${bin_dir}/sward-*")
if(NOT modules)
  message(FATAL_ERROR "BundleRuntime: no Python module (lib/python3/dist-packages/sward/_sward*.so) staged")
endif()

# Names as the binaries' DT_NEEDED entries spell them. glibc's libraries are the system's by definition; libstdc++
# and libgcc_s because the GPU driver shares them; libvulkan because the loader belongs to the driver's installation.
set(system_libraries
  "^ld-linux" "^linux-vdso" "^libc\\.so" "^libm\\.so" "^libmvec\\.so" "^libpthread\\.so" "^libdl\\.so" "^librt\\.so"
  "^libresolv\\.so" "^libutil\\.so" "^libanl\\.so" "^libstdc\\+\\+\\.so" "^libgcc_s\\.so" "^libvulkan\\.so")
file(GET_RUNTIME_DEPENDENCIES
  EXECUTABLES ${executables}
  MODULES ${modules}
  RESOLVED_DEPENDENCIES_VAR resolved
  UNRESOLVED_DEPENDENCIES_VAR unresolved
  CONFLICTING_DEPENDENCIES_PREFIX conflicting
  PRE_EXCLUDE_REGEXES ${system_libraries})
if(unresolved)
  message(FATAL_ERROR "BundleRuntime: libraries not found on this machine: ${unresolved}")
endif()
# /lib is /usr/lib on Debian 12 (merged /usr): one library found under both is the same file. Keep the first.
foreach(name ${conflicting_FILENAMES})
  list(GET conflicting_${name} 0 first)
  list(APPEND resolved ${first})
endforeach()

set(lib_dir ${root}/lib)
set(doc_dir ${root}/share/doc/sward)
file(MAKE_DIRECTORY ${lib_dir} ${doc_dir}/third-party)
set(by_name)
foreach(path ${resolved})
  get_filename_component(name ${path} NAME)
  list(APPEND by_name "${name}|${path}")
endforeach()
list(SORT by_name)
list(REMOVE_DUPLICATES by_name)

set(real_paths)
foreach(entry ${by_name})
  string(REPLACE "|" ";" entry "${entry}")
  list(GET entry 0 name)
  list(GET entry 1 path)
  file(COPY_FILE ${path} ${lib_dir}/${name})
  file(CHMOD ${lib_dir}/${name} PERMISSIONS OWNER_READ OWNER_WRITE GROUP_READ WORLD_READ)
  file(REAL_PATH ${path} real)
  list(APPEND real_paths ${real})
  # dpkg's records name a file under /usr/lib or /lib, whichever the package shipped it in; ask for both.
  string(REGEX REPLACE "^/usr/lib/" "/lib/" other ${real})
  if(other STREQUAL real)
    string(REGEX REPLACE "^/lib/" "/usr/lib/" other ${real})
  endif()
  list(APPEND dpkg_queries ${real} ${other})
endforeach()

# The Debian package of each bundled library, its version and its copyright file.
execute_process(COMMAND dpkg-query -S ${dpkg_queries} OUTPUT_VARIABLE owners ERROR_QUIET)
string(REPLACE "\n" ";" owners "${owners}")
set(manifest "")
set(packages)
foreach(entry ${by_name})
  string(REPLACE "|" ";" entry "${entry}")
  list(GET entry 0 name)
  list(GET entry 1 path)
  file(REAL_PATH ${path} real)
  get_filename_component(real_name ${real} NAME)
  set(package "")
  foreach(line ${owners})
    if(line MATCHES "^([^:]+)(:[a-z0-9]+)?: (.*)/([^/]+)$" AND CMAKE_MATCH_4 STREQUAL real_name)
      set(package ${CMAKE_MATCH_1})
      break()
    endif()
  endforeach()
  if(package STREQUAL "")
    message(FATAL_ERROR "BundleRuntime: no Debian package owns ${real} (${name})")
  endif()
  execute_process(COMMAND dpkg-query -W -f=\${Version} ${package} OUTPUT_VARIABLE version)
  string(APPEND manifest "${name}  ${package}  ${version}\n")
  list(APPEND packages ${package})
endforeach()
list(REMOVE_DUPLICATES packages)
list(SORT packages)
foreach(package ${packages})
  set(copyright /usr/share/doc/${package}/copyright)
  if(NOT EXISTS ${copyright})
    message(FATAL_ERROR "BundleRuntime: ${copyright} missing: the licence of a bundled library must ship with it")
  endif()
  file(REAL_PATH ${copyright} copyright)
  file(MAKE_DIRECTORY ${doc_dir}/third-party/${package})
  file(COPY_FILE ${copyright} ${doc_dir}/third-party/${package}/copyright)
endforeach()

# The newest glibc and libstdc++ symbol versions that anything in the archive needs: the archive's promise.
file(GLOB bundled "${lib_dir}/*.so*")
execute_process(COMMAND objdump -T ${executables} ${modules} ${bundled} OUTPUT_VARIABLE symbols ERROR_QUIET)
foreach(prefix GLIBC GLIBCXX)
  string(REGEX MATCHALL "[( ]${prefix}_[0-9.]+[) ]" found "${symbols}")
  set(newest_${prefix} 0)
  foreach(v ${found})
    string(REGEX REPLACE "[^0-9.]" "" v "${v}")
    if(v VERSION_GREATER newest_${prefix})
      set(newest_${prefix} ${v})
    endif()
  endforeach()
endforeach()

list(LENGTH by_name count)
list(LENGTH packages package_count)
file(WRITE ${doc_dir}/bundled-libraries.txt
  "# The ${count} shared libraries in lib/, from ${package_count} Debian 12 packages (copyright files in\n"
  "# third-party/<package>/copyright). Not bundled: glibc (newest symbol version needed: GLIBC_${newest_GLIBC}),\n"
  "# libstdc++ / libgcc_s (GLIBCXX_${newest_GLIBCXX}), the Vulkan loader libvulkan.so.1 and the GPU driver.\n"
  "# library  package  version\n"
  "${manifest}")
message(STATUS "BundleRuntime: ${count} libraries from ${package_count} packages into ${lib_dir}; needs GLIBC_${newest_GLIBC}, GLIBCXX_${newest_GLIBCXX}")
