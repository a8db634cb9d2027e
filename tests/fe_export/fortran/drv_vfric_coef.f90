! Calls VFRIC_COEF (Abaqus/Explicit, general contact) as Abaqus would.
! stdin: nblock ntemp nfields, then per point: slip_rate pressure temperature fields...
! stdout per point: fCoef(k) fCoefDeriv(k,1:3)
program drv_vfric_coef
  implicit none
  integer :: nblock, ntemp, nfields, nf, k, j
  integer :: jflags(2)
  real(8) :: rdata(3), props(1)
  real(8), allocatable :: fcoef(:), fderiv(:,:), sliprate(:), pressure(:)
  real(8), allocatable :: tempavg(:), fieldavg(:,:)
  character(len=80) :: surfint, surfslv, surfmst
  read (*, *) nblock, ntemp, nfields
  nf = max(nfields, 1)
  allocate (fcoef(nblock), fderiv(nblock, 3), sliprate(nblock))
  allocate (pressure(nblock), tempavg(nblock), fieldavg(nblock, nf))
  fieldavg = 0d0
  do k = 1, nblock
    read (*, *) sliprate(k), pressure(k), tempavg(k), (fieldavg(k, j), j = 1, nf)
  end do
  jflags = 1
  rdata = 0d0
  props = 0d0
  surfint = 'INTPROP'
  surfslv = ' '
  surfmst = ' '
  call vfric_coef(fcoef, fderiv, nblock, 1, ntemp, nfields, jflags, rdata, &
                  surfint, surfslv, surfmst, props, sliprate, pressure, tempavg, fieldavg)
  do k = 1, nblock
    write (*, '(4es26.16e3)') fcoef(k), (fderiv(k, j), j = 1, 3)
  end do
end program drv_vfric_coef
