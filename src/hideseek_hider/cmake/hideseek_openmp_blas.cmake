# libtorch's fully connected layers call BLAS. Debian's default OpenBLAS runs its own threads,
# which fight libtorch's OpenMP threads for the cores, so the hider ran it single-threaded
# (OPENBLAS_NUM_THREADS=1) and those layers used one core while the other waited. The OpenMP
# build (Debian's libopenblas0-openmp, installed by scripts/install_deps.sh) runs on libtorch's
# own OpenMP threads: the training floor runs about 1.25x faster (docs/performance.md). The
# programs that train link it directly, its folder first in their run path, so that the dynamic
# loader takes it before the system's BLAS alternative; without the package they keep the
# system's BLAS (the hider's start-up line says which it has).
function(hideseek_link_openmp_blas target)
  set(dir /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/openblas-openmp)
  if(EXISTS ${dir}/libopenblas.so.0)
    target_link_libraries(${target} -Wl,--no-as-needed ${dir}/libopenblas.so.0 ${dir}/libblas.so.3
      ${dir}/liblapack.so.3 -Wl,--as-needed)
    set_property(TARGET ${target} APPEND PROPERTY BUILD_RPATH ${dir})
    set_property(TARGET ${target} APPEND PROPERTY INSTALL_RPATH ${dir})
  endif()
endfunction()
