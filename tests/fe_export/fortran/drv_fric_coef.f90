! Calls FRIC_COEF (Abaqus/Standard, 2017+ interface) as Abaqus would.
! stdin: nblock ntemp nfields, then per point: slip_rate pressure temperature fields...
! stdout per point: fCoef(k,1) fCoef(k,2) fCoefDeriv(k,1:3,1) fCoefDeriv(k,1:3,2)
! fCoef and fCoefDeriv start at sentinels (-777, -999): the second direction must stay
! untouched for isotropic friction, the first must be written in full.
program drv_fric_coef
  implicit none
  integer :: nblock, ntemp, nfields, nf, k, j
  integer :: jflags(2)
  real(8) :: rdata(3), props(1)
  real(8), allocatable :: fcoef(:,:), fderiv(:,:,:), slipdata(:,:), pressure(:)
  real(8), allocatable :: tempavg(:), fieldavg(:,:)
  character(len=80) :: surfint, surfslv, surfmst
  read (*, *) nblock, ntemp, nfields
  nf = max(nfields, 1)
  allocate (fcoef(nblock, 2), fderiv(nblock, 20, 2), slipdata(nblock, 6))
  allocate (pressure(nblock), tempavg(nblock), fieldavg(nblock, nf))
  slipdata = 0d0
  fieldavg = 0d0
  fderiv = -999d0
  fcoef = -777d0
  do k = 1, nblock
    read (*, *) slipdata(k, 1), pressure(k), tempavg(k), (fieldavg(k, j), j = 1, nf)
  end do
  jflags = 1
  rdata = 0d0
  props = 0d0
  surfint = 'INTPROP'
  surfslv = 'SLAVE'
  surfmst = 'MASTER'
  call fric_coef(fcoef, fderiv, nblock, 1, ntemp, nfields, jflags, rdata, &
                 surfint, surfslv, surfmst, props, slipdata, pressure, tempavg, fieldavg)
  do k = 1, nblock
    write (*, '(8es26.16e3)') fcoef(k, 1), fcoef(k, 2), (fderiv(k, j, 1), j = 1, 3), &
      (fderiv(k, j, 2), j = 1, 3)
    if (any(fderiv(k, 4:20, 1) /= 0d0)) write (*, '(a)') 'UNSET-SLOTS'
    if (any(fderiv(k, :, 2) /= -999d0)) write (*, '(a)') 'SECOND-DIRECTION-WRITTEN'
  end do
end program drv_fric_coef
