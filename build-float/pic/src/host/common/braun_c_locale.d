build-float/pic/src/host/common/braun_c_locale.o: \
 src/host/common/braun_c_locale.c src/host/common/braun_c_locale.h
src/host/common/braun_c_locale.h:
