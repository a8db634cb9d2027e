! Calls VFRIC (Abaqus/Explicit, contact pairs) as Abaqus would: one slave node per contact.
! stdin: ncontact ntemp npred dtime, then per contact:
!        dslip(1:3) fnormal area temperature fstick predef(1:npred)
! stdout per contact: fTangential(1,k) fTangential(2,k)
program drv_vfric
  implicit none
  integer, parameter :: ndir = 3, nfricdir = 2, nfacnod = 4
  integer :: ncontact, ntemp, npred, np, k, j
  integer :: kstep, kinc, nstatevar, nprops, numdeftfv, lconttype
  real(8) :: dtime, timstep, timglb, frictionwork, props(1)
  real(8), allocatable :: ftang(:,:), statev(:,:), dslip(:,:), ftangprev(:,:), fstick(:)
  real(8), allocatable :: area(:), fnormal(:), shape(:,:), coordslv(:,:), coordmst(:,:)
  real(8), allocatable :: dircossl(:,:), dircosn(:,:), tempslv(:), tempmst(:)
  real(8), allocatable :: predefslv(:,:), predefmst(:,:)
  integer, allocatable :: jslvuid(:), jmstuid(:), jconslvid(:), jconmstid(:,:)
  character(len=80) :: surfint, surfslv, surfmst
  read (*, *) ncontact, ntemp, npred, dtime
  np = max(npred, 1)
  allocate (ftang(nfricdir, ncontact), statev(1, ncontact), dslip(ndir, ncontact))
  allocate (ftangprev(ndir, ncontact), fstick(ncontact), area(ncontact))
  allocate (fnormal(ncontact), shape(nfacnod, ncontact), coordslv(ndir, ncontact))
  allocate (coordmst(ndir, nfacnod), dircossl(ndir, ncontact), dircosn(ndir, ncontact))
  allocate (tempslv(ncontact), tempmst(1), predefslv(ncontact, np), predefmst(1, np))
  allocate (jslvuid(ncontact), jmstuid(nfacnod), jconslvid(ncontact))
  allocate (jconmstid(nfacnod, ncontact))
  predefslv = 0d0
  do k = 1, ncontact
    read (*, *) (dslip(j, k), j = 1, ndir), fnormal(k), area(k), tempslv(k), fstick(k), &
      (predefslv(k, j), j = 1, np)
    jconslvid(k) = k
    jslvuid(k) = 100 + k
  end do
  ftang = -999d0
  statev = 0d0; ftangprev = 0d0; shape = 0d0; coordslv = 0d0; coordmst = 0d0
  dircossl = 0d0; dircosn = 0d0; tempmst = 0d0; predefmst = 0d0
  jmstuid = 0; jconmstid = 0; props = 0d0
  kstep = 1; kinc = 1; nstatevar = 1; nprops = 1; numdeftfv = 1; lconttype = 1
  timstep = 0d0; timglb = 0d0; frictionwork = 0d0
  surfint = 'INTPROP'; surfslv = 'SLAVE'; surfmst = 'MASTER'
  call vfric(ftang, statev, kstep, kinc, ncontact, nfacnod, ncontact, nfacnod, &
             nfricdir, ndir, nstatevar, nprops, ntemp, npred, numdeftfv, &
             jslvuid, jmstuid, jconslvid, jconmstid, timstep, timglb, &
             dtime, surfint, surfslv, surfmst, lconttype, &
             dslip, fstick, ftangprev, fnormal, frictionwork, &
             shape, coordslv, coordmst, dircossl, dircosn, props, &
             area, tempslv, predefslv, tempmst, predefmst)
  do k = 1, ncontact
    write (*, '(2es26.16e3)') ftang(1, k), ftang(2, k)
  end do
end program drv_vfric
