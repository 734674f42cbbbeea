" SINUMERIK NC programs: .MPF main programs and .SPF subprograms, in either case.
autocmd BufRead,BufNewFile *.mpf,*.MPF,*.spf,*.SPF setfiletype sinumerik
