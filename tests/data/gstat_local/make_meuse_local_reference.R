# Local (moving-neighbourhood) kriging reference: gstat's nmax on the Meuse data of
# ../shared/reference/gstat (meuse_logzinc.csv, same fixed models as make_meuse_reference.R).
# Run from this folder: Rscript make_meuse_local_reference.R /path/to/shared/reference/gstat
# (R 4.2.2, r-cran-gstat 2.1-0, Debian 12). Writes meuse_local_kriging.csv: for nmax 10 and 30,
# ordinary (logzinc ~ 1) and universal (logzinc ~ x + y, the trend fitted in each neighbourhood)
# kriging predictions and variances at fixed query points.
suppressMessages({library(sp); library(gstat)})
args <- commandArgs(trailingOnly = TRUE)
ref <- if (length(args) > 0) args[1] else "../../../../shared/reference/gstat"
d <- read.csv(file.path(ref, "meuse_logzinc.csv"))
coordinates(d) <- ~x+y
grid <- data.frame(x=c(179000,179500,180000,180500,181000,179300,180700,178800,179850,180300),
                   y=c(330000,330500,331000,331500,332000,333000,329800,331200,332400,330100))
coordinates(grid) <- ~x+y
models <- list(sph=vgm(psill=0.55, model="Sph", range=900, nugget=0.05),
               stable_p1=vgm(psill=0.55, model="Exc", range=400, nugget=0.05, kappa=1.0),
               stable_p2=vgm(psill=0.55, model="Exc", range=600, nugget=0.05, kappa=2.0))
res <- NULL
for (nm in names(models)) for (k in c(10, 30)) {
  m <- models[[nm]]
  ok <- krige(logzinc~1, d, grid, model=m, nmax=k, debug.level=0)
  uk <- krige(logzinc~x+y, d, grid, model=m, nmax=k, debug.level=0)
  res <- rbind(res, data.frame(model=nm, nmax=k, x=coordinates(grid)[,1], y=coordinates(grid)[,2],
                               ok_pred=ok$var1.pred, ok_var=ok$var1.var, uk_pred=uk$var1.pred, uk_var=uk$var1.var))
}
num <- sapply(res, is.numeric)
res[num] <- lapply(res[num], function(v) sprintf("%.17g", v))
write.csv(res, "./meuse_local_kriging.csv", row.names=FALSE, quote=FALSE)
