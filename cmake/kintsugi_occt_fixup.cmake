# Debian's OpenCASCADE package config names /usr/lib/<arch>/libtbb.so, which only
# libtbb-dev installs; the TK libraries already link TBB themselves, so link items that
# are absolute paths to missing files are dropped rather than failing the build.
# Included by io/CMakeLists.txt and by the installed kintsugiConfig.cmake (a consumer
# that finds OpenCASCADE through kintsugi meets the same package config).
foreach(tk ${OpenCASCADE_LIBRARIES})
  if(TARGET ${tk})
    get_target_property(tk_libs ${tk} INTERFACE_LINK_LIBRARIES)
    if(tk_libs)
      set(tk_kept "")
      foreach(item IN LISTS tk_libs)
        if(IS_ABSOLUTE "${item}" AND NOT EXISTS "${item}")
          continue()
        endif()
        list(APPEND tk_kept "${item}")
      endforeach()
      set_target_properties(${tk} PROPERTIES INTERFACE_LINK_LIBRARIES "${tk_kept}")
    endif()
  endif()
endforeach()
