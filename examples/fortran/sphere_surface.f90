! The example surface of examples/c/sphere_surface.h in Fortran, 1-based: a sphere of radius 1
! made of SPHERE_NLAT-1 rings of SPHERE_NLON points and the two poles, triangles counter-clockwise
! seen from outside, patches 1 (south cap), 2 (bands), 3 (north cap). The same operations in the
! same order as the C version (sqrt and divisions only), so the points are the same doubles.
! sphere_in_box_build adds the box [-3, 3]^3 around it (patch 4), as examples/c/boundary_layer.c.
module sphere_surface
  use, intrinsic :: iso_c_binding
  implicit none
  private
  integer, parameter, public :: SPHERE_NLAT = 8, SPHERE_NLON = 16
  integer, parameter, public :: SPHERE_NPOINTS = 2 + (SPHERE_NLAT - 1) * SPHERE_NLON
  integer, parameter, public :: SPHERE_NTRI = 2 * SPHERE_NLON * (SPHERE_NLAT - 1)
  integer, parameter, public :: SPHERE_IN_BOX_NPOINTS = SPHERE_NPOINTS + 8
  integer, parameter, public :: SPHERE_IN_BOX_NTRI = SPHERE_NTRI + 12
  public :: sphere_build, sphere_in_box_build

contains

  ! 1-based index of point j (0-based, taken modulo SPHERE_NLON) of ring k (1 .. SPHERE_NLAT-1).
  integer(c_int32_t) function ring_point(k, j)
    integer, intent(in) :: k, j
    ring_point = int(2 + (k - 1) * SPHERE_NLON + mod(j, SPHERE_NLON), c_int32_t)
  end function

  subroutine sphere_build(xyz, tri, patch)
    real(c_double), intent(out) :: xyz(3, SPHERE_NPOINTS)
    integer(c_int32_t), intent(out) :: tri(3, SPHERE_NTRI), patch(SPHERE_NTRI)
    integer, parameter :: q = SPHERE_NLON / 4
    integer :: k, j, t, p
    real(c_double) :: zd, rd, h, r, z, u, xd, yd, g
    xyz(:, 1) = [0d0, 0d0, -1d0]
    do k = 1, SPHERE_NLAT - 1
      zd = real(2 * k - SPHERE_NLAT, c_double) / real(SPHERE_NLAT, c_double)
      rd = 1d0 - abs(zd)
      h = sqrt(rd * rd + zd * zd)
      r = rd / h
      z = zd / h
      do j = 0, SPHERE_NLON - 1
        u = real(mod(j, q), c_double) / real(q, c_double)
        select case (j / q)
        case (0)
          xd = 1d0 - u
          yd = u
        case (1)
          xd = -u
          yd = 1d0 - u
        case (2)
          xd = -(1d0 - u)
          yd = -u
        case default
          xd = u
          yd = -(1d0 - u)
        end select
        g = sqrt(xd * xd + yd * yd)
        p = ring_point(k, j)
        xyz(:, p) = [r * (xd / g), r * (yd / g), z]
      end do
    end do
    xyz(:, SPHERE_NPOINTS) = [0d0, 0d0, 1d0]
    t = 0
    do j = 0, SPHERE_NLON - 1
      t = t + 1
      tri(:, t) = [1_c_int32_t, ring_point(1, j + 1), ring_point(1, j)]
      patch(t) = 1
    end do
    do k = 1, SPHERE_NLAT - 2
      do j = 0, SPHERE_NLON - 1
        t = t + 1
        tri(:, t) = [ring_point(k, j), ring_point(k, j + 1), ring_point(k + 1, j + 1)]
        patch(t) = 2
        t = t + 1
        tri(:, t) = [ring_point(k, j), ring_point(k + 1, j + 1), ring_point(k + 1, j)]
        patch(t) = 2
      end do
    end do
    do j = 0, SPHERE_NLON - 1
      t = t + 1
      tri(:, t) = [ring_point(SPHERE_NLAT - 1, j), ring_point(SPHERE_NLAT - 1, j + 1), &
                   int(SPHERE_NPOINTS, c_int32_t)]
      patch(t) = 3
    end do
  end subroutine

  ! The sphere, then the box's 8 corners (corner i at -3 or 3 by the bits of i - 1: x, y, z) and
  ! 12 triangles (patch 4), counter-clockwise seen from outside. The sphere is a cavity of the
  ! box: the validation's repairs (on by default) turn it inward.
  subroutine sphere_in_box_build(xyz, tri, patch)
    real(c_double), intent(out) :: xyz(3, SPHERE_IN_BOX_NPOINTS)
    integer(c_int32_t), intent(out) :: tri(3, SPHERE_IN_BOX_NTRI), patch(SPHERE_IN_BOX_NTRI)
    integer(c_int32_t), parameter :: box_tri(3, 12) = reshape([0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, &
        0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5], [3, 12])
    integer :: i
    call sphere_build(xyz(:, 1:SPHERE_NPOINTS), tri(:, 1:SPHERE_NTRI), patch(1:SPHERE_NTRI))
    do i = 0, 7
      xyz(:, SPHERE_NPOINTS + 1 + i) = merge(3d0, -3d0, [btest(i, 0), btest(i, 1), btest(i, 2)])
    end do
    tri(:, SPHERE_NTRI + 1:) = box_tri + int(SPHERE_NPOINTS + 1, c_int32_t)
    patch(SPHERE_NTRI + 1:) = 4
  end subroutine

end module sphere_surface
