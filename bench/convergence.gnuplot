# Log-log error against time, one PNG per group of settings: gnuplot -e "csv='X.csv'; out='X'" convergence.gnuplot
set datafile separator ","
set terminal pngcairo size 800,560 noenhanced
set logscale xy
set xlabel "seconds"
set ylabel "relative MSE"
set key outside right
set grid
groups = "integrator alpha photons radius direct"
do for [g in groups] {
    set output sprintf("%s_%s.png", out, g)
    set title sprintf("%s: error against time", g)
    settings = system(sprintf("awk -F, 'NR>1 && $2==\"%s\" {print $3}' %s | uniq | tr ' ' '_' | tr '\\n' ' '", g, csv))
    plot for [s in settings] sprintf("< awk -F, 'NR>1 && $2==\"%s\" {gsub(/ /,\"_\",$3); if ($3==\"%s\") print $4\",\"$7}' %s", g, s, csv) \
        using 1:2 with linespoints title s
}
